/* smoothing_fixture.c — context, smoother, scenes and measures of the smoothing tests. */
#include "smoothing_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render_fixture.h"

#define SCENE_DEPTH 5.0f
/* 2 / (V cot 20°): the view-space size of a pixel at unit depth, 40° vertical fov. */
#define PIXEL_SCALE (2.0f / (SF_H * 2.7474774f))

bool smoothing_open(smoothing_fixture *sf)
{
    *sf = (smoothing_fixture){0};
    fc_gpu_choice gpu;
    fc_error err = {0};
    if (!fixture_gpu_choice(&gpu))
        return false;
    if (fc_gl_context_create(&gpu, &sf->gl, &err) != FC_OK) {
        fprintf(stderr, "no GL context: %s\n", err.message);
        return false;
    }
    sf->input = fc_render_target_init(GL_R32F, false, false);
    if (fc_smoother_create(NULL, &sf->smoother, &err) != FC_OK ||
        fc_render_target_resize(&sf->input, SF_W, SF_H, &err) != FC_OK) {
        fprintf(stderr, "smoother set-up: %s\n", err.message);
        smoothing_close(sf);
        return false;
    }
    return true;
}

void smoothing_close(smoothing_fixture *sf)
{
    if (sf->gl) {
        fc_smoother_destroy(&sf->smoother);
        fc_render_target_release(&sf->input);
    }
    fc_gl_context_destroy(sf->gl);
    *sf = (smoothing_fixture){0};
}

fc_smoothing_params smoothing_params(fc_smoothing method, uint32_t iterations, float smooth_scale)
{
    return (fc_smoothing_params){
        .method = method,
        .iterations = iterations,
        /* Square pixels: Cx = 2 / (W Fx) = 2 / (H Fy) = Cy. */
        .pixel_scale = {PIXEL_SCALE, PIXEL_SCALE},
        .depth_jump = SF_DEPTH_JUMP,
        .particle_radius = SF_RADIUS,
        .reference_depth = SCENE_DEPTH,
        .smooth_scale = smooth_scale,
    };
}

fc_code smoothing_read(const fc_render_target *target, float *out)
{
    fc_error err = {0};
    fc_image img = {0};
    fc_code code = read_target(target, 1, &img, &err);
    if (code == FC_OK) {
        /* The readback is top to bottom; put it back in GL order. */
        const float *rows = img.pixels;
        for (uint32_t y = 0; y < img.height; y++)
            memcpy(out + (size_t)y * img.width, rows + (size_t)(img.height - 1 - y) * img.width,
                   img.width * sizeof(float));
    } else {
        fprintf(stderr, "readback: %s\n", err.message);
    }
    fc_image_free(&img);
    return code;
}

fc_code smoothing_apply(smoothing_fixture *sf, const float *depth, const fc_smoothing_params *params, float *out)
{
    fc_error err = {0};
    glTextureSubImage2D(sf->input.color, 0, 0, 0, SF_W, SF_H, GL_RED, GL_FLOAT, depth);
    const fc_render_target *result = NULL;
    fc_code code = fc_smoother_run(&sf->smoother, &sf->input, params, &result, &err);
    if (code != FC_OK) {
        fprintf(stderr, "smoothing: %s\n", err.message);
        return code;
    }
    return smoothing_read(result, out);
}

int smoothing_method_by_name(const char *name)
{
    static const char *const names[] = {"none", "curvature", "bilateral", "binomial", "narrow"};
    for (int i = 0; i < (int)(sizeof names / sizeof names[0]); i++)
        if (strcmp(name, names[i]) == 0)
            return i;   /* the order of fc_smoothing */
    return -1;
}

void scene_plane(float *depth, float z)
{
    for (int i = 0; i < SF_PIXELS; i++)
        depth[i] = z;
}

void scene_bump(float *depth, float z, float height, float sigma_px)
{
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++) {
            float dx = x - SF_W / 2.0f, dy = y - SF_H / 2.0f;
            depth[y * SF_W + x] = z - height * expf(-(dx * dx + dy * dy) / (2.0f * sigma_px * sigma_px));
        }
}

void scene_add_disc(float *depth, float cx, float cy, float radius_px, float z)
{
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++) {
            float dx = x + 0.5f - cx, dy = y + 0.5f - cy;
            float *d = depth + y * SF_W + x;
            if (dx * dx + dy * dy <= radius_px * radius_px && (*d <= 0.0f || z < *d))
                *d = z;
        }
}

static bool same_surface(float a, float b, float jump)
{
    return a > 0.0f && b > 0.0f && fabsf(a - b) <= jump;
}

double total_curvature(const float *depth, float depth_jump)
{
    double sum = 0.0;
    for (int y = 1; y < SF_H - 1; y++)
        for (int x = 1; x < SF_W - 1; x++) {
            const float *p = depth + y * SF_W + x;
            if (same_surface(p[0], p[1], depth_jump) && same_surface(p[0], p[-1], depth_jump) &&
                same_surface(p[0], p[SF_W], depth_jump) && same_surface(p[0], p[-SF_W], depth_jump))
                sum += fabs((double)p[1] + p[-1] + p[SF_W] + p[-SF_W] - 4.0 * p[0]);
        }
    return sum;
}

void silhouette_distance(const float *depth, uint8_t *distance)
{
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++) {
            float here = depth[y * SF_W + x];
            int best = SF_FAR;
            for (int v = y - SF_FAR + 1; v < y + SF_FAR; v++)
                for (int u = x - SF_FAR + 1; u < x + SF_FAR; u++) {
                    if (u < 0 || v < 0 || u >= SF_W || v >= SF_H)
                        continue;
                    float there = depth[v * SF_W + u];
                    bool same = (here <= 0.0f && there <= 0.0f) || same_surface(here, there, SF_DEPTH_JUMP);
                    int d = abs(u - x) > abs(v - y) ? abs(u - x) : abs(v - y);
                    if (!same && d < best)
                        best = d;
                }
            distance[y * SF_W + x] = (uint8_t)best;
        }
}
