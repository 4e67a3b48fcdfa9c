/* render_camera.h — the camera over a sequence: framed once on the bounding
 * box of all its frames (so it does not jump from frame to frame), or the
 * --eye/--target one, and turned about the target for --orbit. */
#ifndef FC_RENDER_CAMERA_H
#define FC_RENDER_CAMERA_H

#include <stdint.h>

#include "fluidcast_types.h"
#include "render_inputs.h"
#include "snapshot_options.h"
#include "up_choice.h"

typedef struct fc_sequence_bounds {
    float lo[3], hi[3];   /* the union of the frames' boxes */
    uint32_t framed;      /* frames read: the box covers paths[0..framed) */
} fc_sequence_bounds;

/* Reads every file for its bounding box, in order, stopping quietly at the
 * first one that cannot be read (the render reports it when its turn comes,
 * after rendering the frames before it, which the box covers). The first file
 * is kept in *first (free it with fc_frame_free): the up guess and the radius
 * estimate come from it. Its failure is the only error, naming the file. */
fc_code fc_sequence_bounds_read(const fc_render_inputs *in, const fc_read_options *options, fc_sequence_bounds *out,
                                fc_frame *first,
                                fc_error *err);

/* The sequence's camera as fc_snapshot_camera makes it for a frame whose box
 * is the sequence's. FC_ERR_USAGE for an invalid camera. */
fc_code fc_sequence_camera(const fc_snapshot_options *view, const fc_sequence_bounds *bounds, fc_up_choice *up,
                           fc_camera *cam, fc_error *err);

/* `base` with its eye turned by `degrees` about the line through the target
 * along base->up (counter-clockwise seen from above). */
void fc_orbit_camera(const fc_camera *base, double degrees, fc_camera *out);

#endif
