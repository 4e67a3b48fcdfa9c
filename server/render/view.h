/* view.h — camera transforms of a render: right-handed OpenGL look-at and a
 * perspective whose near/far planes enclose the uploaded particles. */
#ifndef FC_VIEW_H
#define FC_VIEW_H

#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_view {
    float view[16];            /* world -> view, column-major; the camera looks down -z */
    float view_to_world[9];    /* rotation of the inverse, column-major: right, up, backward */
    float eye[3];
    float fx, fy;              /* P[0][0], P[1][1]: focal lengths in NDC units */
    float p22, p32;            /* P[2][2], P[3][2]: the depth part of the projection */
    float near_plane, far_plane;
    uint32_t width, height;
} fc_view;

/* The transforms of a (validated) camera for particles of `radius` inside the
 * box [lo, hi]. Near and far hug the box grown by the radius, so no sphere is
 * clipped and the depth buffer's precision is spent on the fluid. */
void fc_view_from_camera(const fc_camera *cam, const float lo[3], const float hi[3], float radius, fc_view *out);

/* (Cx, Cy) of van der Laan et al. 2009, eq. 3: the view-space size of one
 * pixel at unit depth, 2 / (V F) per axis. */
void fc_view_pixel_scale(const fc_view *v, float *cx, float *cy);

/* Rotates a view-space direction into world space. */
void fc_view_direction_to_world(const fc_view *v, const float view_dir[3], float world_dir[3]);

#endif
