/* vec3.h — the few 3-vector operations the camera set-up needs. */
#ifndef FC_VEC3_H
#define FC_VEC3_H

#include <math.h>

static inline float fc_dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void fc_cross3(const float a[3], const float b[3], float out[3])
{
    float x = a[1] * b[2] - a[2] * b[1];
    float y = a[2] * b[0] - a[0] * b[2];
    float z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

/* Scales v to unit length; a zero vector stays zero. */
static inline void fc_normalize3(float v[3])
{
    float len = sqrtf(fc_dot3(v, v));
    if (len > 0.0f) {
        v[0] /= len;
        v[1] /= len;
        v[2] /= len;
    }
}

#endif
