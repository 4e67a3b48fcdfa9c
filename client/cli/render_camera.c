/* render_camera.c — see render_camera.h. */
#include "render_camera.h"

#include <math.h>
#include <string.h>

#include "fc_frame.h"
#include "render_reader.h"
#include "snapshot_camera.h"

#define DEG_TO_RAD 0.017453292519943295

static fc_code grow_box(fc_sequence_bounds *b, const fc_frame *frame, fc_error *err)
{
    fc_framing_box box;
    fc_code code = fc_framing_box_of(frame, &box, err);
    if (code != FC_OK)
        return code;
    if (b->framed == 0)
        b->box = box;
    else
        fc_framing_box_union(&b->box, &box);
    b->framed++;
    return FC_OK;
}

fc_code fc_sequence_bounds_read(const fc_render_inputs *in, const fc_read_options *options, fc_sequence_bounds *out,
                                fc_frame *first,
                                fc_error *err)
{
    memset(out, 0, sizeof *out);
    fc_code code = fc_load_particles_checked(in->paths[0], options, first, err);
    if (code == FC_OK)
        code = grow_box(out, first, err);
    for (uint32_t i = 1; code == FC_OK && i < in->count; i++) {
        fc_frame frame = {0};
        fc_error ignored;
        bool read = fc_load_particles_checked(in->paths[i], options, &frame, &ignored) == FC_OK;
        if (read)
            code = grow_box(out, &frame, err);
        fc_frame_free(&frame);
        if (!read)
            break;
    }
    return code;
}

fc_code fc_sequence_camera(const fc_snapshot_options *view, const fc_sequence_bounds *bounds, fc_up_choice *up,
                           fc_camera *cam, fc_error *err)
{
    return fc_snapshot_camera(view, &bounds->box, up, cam, err);
}

/* Rodrigues: v cos a + (k x v) sin a + k (k . v)(1 - cos a), k a unit vector. */
static void rotate(const double k[3], double angle, const double v[3], double out[3])
{
    double c = cos(angle), s = sin(angle);
    double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    const double kxv[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    for (int i = 0; i < 3; i++)
        out[i] = v[i] * c + kxv[i] * s + k[i] * kv * (1.0 - c);
}

void fc_orbit_camera(const fc_camera *base, double degrees, fc_camera *out)
{
    *out = *base;
    double length = sqrt((double)base->up[0] * base->up[0] + (double)base->up[1] * base->up[1] +
                         (double)base->up[2] * base->up[2]);
    if (!(length > 0.0) || degrees == 0.0)
        return;
    const double axis[3] = {base->up[0] / length, base->up[1] / length, base->up[2] / length};
    double offset[3], turned[3];
    for (int k = 0; k < 3; k++)
        offset[k] = (double)base->eye[k] - base->target[k];
    rotate(axis, degrees * DEG_TO_RAD, offset, turned);
    for (int k = 0; k < 3; k++)
        out->eye[k] = (float)(base->target[k] + turned[k]);
}
