/* wire_frame_io.h — internal to the proto libraries: the part of a frame's
 * layout that FRAME and the quantised packed layout share. */
#ifndef FC_WIRE_FRAME_IO_H
#define FC_WIRE_FRAME_IO_H

#include "wire_io.h"

/* Reads the optional attribute arrays that follow the positions into the
 * frame's arrays, requires the payload to end there and the frame to be valid. */
fc_code wire_get_frame_attributes(wire_reader *r, const fc_frame *frame, fc_error *err);

/* An owned copy of a view's arrays (fc_frame_free releases it). */
fc_code wire_frame_from_view(const fc_frame *view, fc_frame *out, fc_error *err);

#endif
