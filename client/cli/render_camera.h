/* render_camera.h — the camera over a sequence: framed once on the union of
 * all its frames' framing boxes (framing_bounds.h: the fluid, not droplets
 * flung far from it; one camera, so it does not jump from frame to frame),
 * or the --eye/--target one, and turned about the target for --orbit. */
#ifndef FC_RENDER_CAMERA_H
#define FC_RENDER_CAMERA_H

#include <stdint.h>

#include "fluidcast_types.h"
#include "framing_bounds.h"
#include "render_inputs.h"
#include "snapshot_options.h"
#include "up_choice.h"

typedef struct fc_sequence_bounds {
    fc_framing_box box;   /* the union of the frames' framing boxes; left_out: the most of any frame */
    uint32_t framed;      /* frames read: the box covers paths[0..framed) */
} fc_sequence_bounds;

/* Reads every file for its framing box, in order, stopping quietly at the
 * first one that cannot be read (the render reports it when its turn comes,
 * after rendering the frames before it, which the box covers). The first file
 * is kept in *first (free it with fc_frame_free): the up guess and the radius
 * estimate come from it. Its failure is the only read error, naming the file;
 * FC_ERR_NOMEM when a frame's framing sample cannot be allocated. */
fc_code fc_sequence_bounds_read(const fc_render_inputs *in, const fc_read_options *options, fc_sequence_bounds *out,
                                fc_frame *first,
                                fc_error *err);

/* The sequence's camera: fc_snapshot_camera on the sequence's box.
 * FC_ERR_USAGE for an invalid camera. */
fc_code fc_sequence_camera(const fc_snapshot_options *view, const fc_sequence_bounds *bounds, fc_up_choice *up,
                           fc_camera *cam, fc_error *err);

/* `base` with its eye turned by `degrees` about the line through the target
 * along base->up (counter-clockwise seen from above). */
void fc_orbit_camera(const fc_camera *base, double degrees, fc_camera *out);

#endif
