/* wire_frame_io.h — internal to the proto libraries: the part of a frame's
 * layout that FRAME and the quantised packed layout share. */
#ifndef FC_WIRE_FRAME_IO_H
#define FC_WIRE_FRAME_IO_H

#include "wire_io.h"

/* Reads the optional attribute arrays that follow the positions, requires the
 * payload to end there and the frame to be valid. On success *out takes
 * *frame; on failure *frame is freed, so the caller never frees it. */
fc_code wire_get_frame_attributes(wire_reader *r, fc_frame *frame, fc_frame *out, fc_error *err);

#endif
