/* reader_select.h — internal to the particle readers: applying --select
 * (particle_reader.h's fc_select) to a frame just read. */
#ifndef FC_READER_SELECT_H
#define FC_READER_SELECT_H

#include "particle_reader.h"
#include "reader_extras.h"

/* Keeps the particles of *frame (and of extras, in step) for which every
 * selection of o holds, in their order; x, y, z are compared as positions + offset
 * (the file's coordinates when the positions were recentred). FC_ERR_USAGE naming the file and the
 * selection for an attribute neither the frame nor extras has (listing those
 * it has) and for a selection that keeps no particle. */
fc_code fc_select_apply(fc_frame *frame, fc_read_extras *extras, const fc_read_options *o, const double offset[3],
                        const char *name, fc_error *err);

#endif
