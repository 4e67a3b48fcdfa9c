/* render_reader.h — reads a sequence's particle files on a thread of its own,
 * at most two frames ahead of the renderer (a bounded queue), so the next
 * frame is in memory when the daemon is ready for it and the daemon never
 * waits for the disk. Frames come out in order; the first file that cannot be
 * read comes out as its error, and the reader reads nothing after it. */
#ifndef FC_RENDER_READER_H
#define FC_RENDER_READER_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "particle_reader.h"

#define FC_RENDER_READ_AHEAD 2

typedef struct fc_render_reader fc_render_reader;

typedef struct fc_read_frame {
    uint32_t slot;        /* the position of the file in the list given to start */
    fc_frame frame;       /* the particles (the taker frees them with fc_frame_free) */
    fc_code code;         /* FC_OK, or why the file could not be read (err says, naming it) */
    fc_error err;
} fc_read_frame;

/* Reads and checks one particle file as the CLI does (cli_particles.h), into
 * an error value: FC_ERR_IO/FC_ERR_PARSE... naming the file, also for a file
 * with no particles or non-finite values. */
fc_code fc_load_particles_checked(const char *path, const fc_read_options *options, fc_frame *frame, fc_error *err);

/* Starts reading paths[0..count) with the reader options (the strings and options must outlive the reader).
 * FC_ERR_NOMEM or FC_ERR_IO when the thread cannot be made. */
fc_code fc_render_reader_start(char *const *paths, uint32_t count, const fc_read_options *options,
                              fc_render_reader **out, fc_error *err);

/* Waits for the next frame; false when every file was handed out or the
 * reader stopped after a failure. */
bool fc_render_reader_next(fc_render_reader *r, fc_read_frame *out);

/* Stops the thread (at once, even mid-sequence), frees the frames it still
 * holds and the reader. NULL is ignored. */
void fc_render_reader_stop(fc_render_reader *r);

#endif
