/* camera_path_curve.c — fc_camera_path_at (camera_path.h): the camera between
 * keyframes, a Hermite segment whose tangents are the Catmull-Rom chords
 * measured in frames, so unevenly spaced keyframes do not overshoot. */
#include <stddef.h>

#include "camera_path.h"

/* The last keyframe at or before `frame` (0 when frame is before the first). */
static uint32_t segment_of(const fc_camera_path *p, uint32_t frame)
{
    uint32_t lo = 0, hi = p->count - 1;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo + 1) / 2;
        if (p->keys[mid].frame <= frame)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/* The slope at keyframe i of member `offset` (eye or target): the chord
 * between its neighbours (one of them itself at the ends) per frame. */
static void tangent(const fc_camera_path *p, uint32_t i, size_t offset, double out[3])
{
    uint32_t a = i > 0 ? i - 1 : i, b = i + 1 < p->count ? i + 1 : i;
    const float *pa = (const float *)((const char *)&p->keys[a] + offset);
    const float *pb = (const float *)((const char *)&p->keys[b] + offset);
    double dt = (double)p->keys[b].frame - (double)p->keys[a].frame;
    for (int k = 0; k < 3; k++)
        out[k] = dt > 0 ? ((double)pb[k] - pa[k]) / dt : 0.0;
}

static void hermite(const fc_camera_path *p, uint32_t i, double s, size_t offset, float out[3])
{
    const float *p0 = (const float *)((const char *)&p->keys[i] + offset);
    const float *p1 = (const float *)((const char *)&p->keys[i + 1] + offset);
    double h = (double)p->keys[i + 1].frame - (double)p->keys[i].frame;
    double m0[3], m1[3];
    tangent(p, i, offset, m0);
    tangent(p, i + 1, offset, m1);
    double s2 = s * s, s3 = s2 * s;
    double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    for (int k = 0; k < 3; k++)
        out[k] = (float)(h00 * p0[k] + h10 * h * m0[k] + h01 * p1[k] + h11 * h * m1[k]);
}

static void key_up(const fc_camera_key *key, const fc_camera *base, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = key->has_up ? key->up[k] : base->up[k];
}

static double key_fov(const fc_camera_key *key, const fc_camera *base)
{
    return key->has_fov ? key->fov_deg : base->fov_y_deg;
}

/* A keyframe's own camera, its values exactly as parsed: before the first,
 * after the last, or on one. */
static void hold(const fc_camera_key *key, const fc_camera *base, fc_camera *out)
{
    for (int k = 0; k < 3; k++) {
        out->eye[k] = key->eye[k];
        out->target[k] = key->target[k];
        out->up[k] = key->has_up ? key->up[k] : base->up[k];
    }
    out->fov_y_deg = key->has_fov ? key->fov_deg : base->fov_y_deg;
}

void fc_camera_path_at(const fc_camera_path *p, uint32_t frame, const fc_camera *base, fc_camera *out)
{
    *out = *base;
    uint32_t i = segment_of(p, frame);
    if (frame <= p->keys[i].frame || i + 1 == p->count) {
        hold(&p->keys[i], base, out);
        return;
    }
    const fc_camera_key *a = &p->keys[i], *b = &p->keys[i + 1];
    double s = ((double)frame - a->frame) / ((double)b->frame - a->frame);
    hermite(p, i, s, offsetof(fc_camera_key, eye), out->eye);
    hermite(p, i, s, offsetof(fc_camera_key, target), out->target);
    double up_a[3], up_b[3];
    key_up(a, base, up_a);
    key_up(b, base, up_b);
    for (int k = 0; k < 3; k++)
        out->up[k] = (float)(up_a[k] + s * (up_b[k] - up_a[k]));
    out->fov_y_deg = (float)(key_fov(a, base) + s * (key_fov(b, base) - key_fov(a, base)));
}
