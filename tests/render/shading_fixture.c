/* shading_fixture.c — frame rendering and pixel access for the shading tests. */
#include "shading_fixture.h"

#include <stdio.h>

fc_code render_frame(render_fixture *f, const fc_frame *frame, const fc_camera *cam, const fc_settings *settings,
                     const fc_scene_textures *scene, fc_aov aov, int want_u8, fc_image *out)
{
    fc_error err = {0};
    fc_code code = fc_pipeline_upload(f->pipeline, frame, NULL, &err);
    if (code == FC_OK)
        code = fc_pipeline_render_scene(f->pipeline, cam, settings, scene, aov, want_u8, out, NULL, &err);
    if (code != FC_OK)
        fprintf(stderr, "render failed: %s\n", err.message);
    return code;
}

float channel_f32(const fc_image *img, uint32_t x, uint32_t row, uint32_t c)
{
    return ((const float *)img->pixels)[((size_t)row * img->width + x) * img->channels + c];
}

uint8_t channel_u8(const fc_image *img, uint32_t x, uint32_t row, uint32_t c)
{
    return ((const uint8_t *)img->pixels)[((size_t)row * img->width + x) * img->channels + c];
}

void make_sheet(float *positions, int size, float spacing)
{
    float offset = 0.5f * (float)(size - 1);
    for (int i = 0; i < size; i++)
        for (int j = 0; j < size; j++) {
            float *p = positions + 3 * (i * size + j);
            p[0] = ((float)i - offset) * spacing;
            p[1] = ((float)j - offset) * spacing;
            p[2] = 0.0f;
        }
}
