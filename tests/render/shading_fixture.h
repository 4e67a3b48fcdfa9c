/* shading_fixture.h — what the shading tests (test_shading_*.c) share on top
 * of render_fixture.h: rendering whole frames (densities, velocities, ids)
 * with scene textures, and reading pixels of multi-channel images. */
#ifndef FC_SHADING_FIXTURE_H
#define FC_SHADING_FIXTURE_H

#include "render_fixture.h"

/* Uploads `frame` and renders one image with `scene` (NULL = built-in). */
fc_code render_frame(render_fixture *f, const fc_frame *frame, const fc_camera *cam, const fc_settings *settings,
                     const fc_scene_textures *scene, fc_aov aov, int want_u8, fc_image *out);

/* Channel c of pixel (x, row) of a float image with any number of channels. */
float channel_f32(const fc_image *img, uint32_t x, uint32_t row, uint32_t c);

/* Channel c of pixel (x, row) of an 8-bit image with any number of channels. */
uint8_t channel_u8(const fc_image *img, uint32_t x, uint32_t row, uint32_t c);

/* A size x size grid of particles `spacing` apart in the plane z = 0,
 * centred on the origin: a flat sheet facing an axis_camera. */
void make_sheet(float *positions, int size, float spacing);

#endif
