/* test_constant_paths.c — the background and composite programs take their
 * per-draw values as uniforms or as flat inputs (flat_constants.h: flat on
 * llvmpipe, where uniform reads cost a gather each, uniforms on a GPU;
 * fc_pipeline_config.constants chooses). Both paths must give the same images
 * bit for bit. A pipeline of each renders 9 looks (default, shadow off, noise
 * and foam, colour by speed, a client background, a cube map, an opaque mesh,
 * a glass mesh, another exposure) from 2 cameras (low, with the horizon and
 * the sky in view, and from above), each 8-bit and float, and the images are
 * compared byte for byte. The test also checks that each pipeline took the
 * path it was told (else it would compare a path with itself). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

#define WIDTH 96
#define HEIGHT 72
#define LATTICE 0.0625f
#define STEPS 5
#define RADIUS 0.05f
#define LOOKS 9
#define CAMERAS 2
#define IMAGES (LOOKS * CAMERAS * 2)

static const char *const look_names[LOOKS] = {"default", "shadow off", "noise and foam", "colour by speed",
                                              "client background", "cube map", "opaque mesh", "glass mesh",
                                              "exposure +1"};

/* A ball of particles over the floor z = 0, each moving at a speed that grows with its height. */
static bool ball(fc_frame *frame)
{
    size_t max = (2 * STEPS + 1) * (2 * STEPS + 1) * (2 * STEPS + 1);
    float *p = malloc(3 * sizeof(float) * max), *v = malloc(3 * sizeof(float) * max);
    uint64_t n = 0;
    for (int i = -STEPS; p && v && i <= STEPS; i++)
        for (int j = -STEPS; j <= STEPS; j++)
            for (int k = -STEPS; k <= STEPS; k++)
                if (i * i + j * j + k * k <= STEPS * STEPS) {
                    p[3 * n] = (float)i * LATTICE;
                    p[3 * n + 1] = (float)j * LATTICE;
                    p[3 * n + 2] = (float)k * LATTICE + 0.5f;
                    v[3 * n] = v[3 * n + 1] = 0.0f;
                    v[3 * n + 2] = (float)(k + STEPS) / (2.0f * STEPS);
                    n++;
                }
    *frame = (fc_frame){.count = n, .positions = p, .velocity = v};
    return p && v;
}

/* The scene textures: a gradient background and a cube map of six flat colours. */
static fc_scene_textures *textures(fc_pipeline *p, bool with_background, bool with_cube)
{
    float background_pixels[4 * 4 * 3], face_pixels[6][4 * 3];
    for (int i = 0; i < 16; i++) {
        background_pixels[3 * i] = 0.1f + 0.05f * (float)i;
        background_pixels[3 * i + 1] = 0.6f - 0.03f * (float)i;
        background_pixels[3 * i + 2] = 0.3f;
    }
    fc_image background = {.width = 4, .height = 4, .channels = 3, .type = FC_PIXEL_F32,
                           .pixels = (unsigned char *)background_pixels};
    fc_image faces[6];
    for (int f = 0; f < 6; f++) {
        for (int i = 0; i < 4; i++) {
            face_pixels[f][3 * i] = 0.15f * (float)f;
            face_pixels[f][3 * i + 1] = 0.9f - 0.1f * (float)f;
            face_pixels[f][3 * i + 2] = 0.5f;
        }
        faces[f] = (fc_image){.width = 2, .height = 2, .channels = 3, .type = FC_PIXEL_F32,
                              .pixels = (unsigned char *)face_pixels[f]};
    }
    fc_scene_textures *t = NULL;
    fc_error err = {0};
    fc_code code = fc_scene_textures_create(p, with_background ? &background : NULL, with_cube ? faces : NULL, &t,
                                            &err);
    CHECK_MSG(code == FC_OK, "scene textures: %s", err.message);
    return t;
}

/* A pane (two triangles) beside the ball, standing on the floor. */
static fc_mesh_buffers *pane(fc_pipeline *p)
{
    static float vertices[12] = {-0.2f, -0.45f, 0.0f, 0.6f, -0.45f, 0.0f, 0.6f, -0.45f, 0.7f, -0.2f, -0.45f, 0.7f};
    static uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    fc_mesh mesh = {.vertex_count = 4, .triangle_count = 2, .vertices = vertices, .indices = indices, .opacity = 1};
    fc_mesh_buffers *buffers = NULL;
    fc_error err = {0};
    CHECK_MSG(fc_mesh_buffers_create(p, &mesh, &buffers, &err) == FC_OK, "mesh buffers: %s", err.message);
    return buffers;
}

static fc_camera camera(int which)
{
    fc_camera cam = {.target = {0.0f, 0.0f, 0.4f}, .up = {0.0f, 0.0f, 1.0f}, .fov_y_deg = 40.0f, .width = WIDTH,
                     .height = HEIGHT};
    const float low[3] = {0.5f, -3.0f, 0.6f}, above[3] = {0.3f, -0.8f, 3.0f};
    memcpy(cam.eye, which == 0 ? low : above, sizeof low);
    return cam;
}

typedef struct scene_parts {
    fc_scene_textures *background, *cube;
    fc_mesh_buffers *pane;
} scene_parts;

static fc_settings look_settings(int look)
{
    fc_settings s;
    fc_settings_default(&s);
    s.radius = RADIUS;
    s.shadow = look != 1;
    if (look == 2) {
        s.noise = 0.3f;
        s.foam = 1.0f;
    }
    if (look == 3) {
        s.color_by = FC_COLOR_BY_SPEED;
        s.color_range[0] = 0.0f;
        s.color_range[1] = 1.0f;
    }
    if (look == 8)
        s.exposure = 1.0f;
    return s;
}

/* Image k of IMAGES: look, camera, then 8-bit before float. */
static bool render(fc_pipeline *p, const scene_parts *parts, int k, fc_image *out)
{
    int look = k / (2 * CAMERAS), want_u8 = k % 2 == 0;
    fc_settings s = look_settings(look);
    fc_scene_mesh mesh = {.buffers = parts->pane, .color = {0.8f, 0.5f, 0.3f}, .opacity = look == 7 ? 0.4f : 1.0f};
    mesh.transform[0] = mesh.transform[5] = mesh.transform[10] = 1.0f;   /* 3x4: identity */
    fc_render_scene scene = {.textures = look == 4 ? parts->background : look == 5 ? parts->cube : NULL,
                             .meshes = look == 6 || look == 7 ? &mesh : NULL,
                             .mesh_count = look == 6 || look == 7 ? 1 : 0};
    fc_camera cam = camera(k / 2 % CAMERAS);
    fc_error err = {0};
    fc_code code = fc_pipeline_render_with(p, &cam, &s, &scene, FC_AOV_COLOR, want_u8, out, NULL, &err);
    CHECK_MSG(code == FC_OK, "render %d (%s): %s", k, look_names[look], err.message);
    return code == FC_OK;
}

/* Every image through a pipeline that takes `path`; false after a CHECK. */
static bool render_all(fc_constants_path path, const fc_frame *frame, fc_image images[IMAGES])
{
    fc_pipeline *p = NULL;
    fc_error err = {0};
    fc_code code = fc_pipeline_create(&(fc_pipeline_config){.constants = path}, &p, &err);
    CHECK_MSG(code == FC_OK, "pipeline: %s", err.message);
    if (code != FC_OK)
        return false;
    bool flat = path == FC_CONSTANTS_FLAT;
    CHECK_MSG(fc_pipeline_flat_constants(p) == flat, "the pipeline told %s took the other path",
              flat ? "flat" : "uniforms");
    scene_parts parts = {textures(p, true, false), textures(p, false, true), pane(p)};
    bool ok = parts.background && parts.cube && parts.pane && fc_pipeline_flat_constants(p) == flat;
    code = ok ? fc_pipeline_upload(p, frame, NULL, &err) : FC_OK;
    CHECK_MSG(code == FC_OK, "upload: %s", err.message);
    for (int k = 0; ok && code == FC_OK && k < IMAGES; k++)
        ok = render(p, &parts, k, &images[k]);
    fc_mesh_buffers_destroy(parts.pane);
    fc_scene_textures_destroy(parts.background);
    fc_scene_textures_destroy(parts.cube);
    fc_pipeline_destroy(p);
    return ok && code == FC_OK;
}

/* Differing pixels of two images of the same render, and the largest byte difference. */
static int differing_pixels(const fc_image *a, const fc_image *b, int *largest)
{
    size_t pixel = fc_image_size(a) / ((size_t)a->width * a->height);
    int count = 0;
    *largest = 0;
    for (size_t i = 0; i < (size_t)a->width * a->height; i++) {
        const unsigned char *x = a->pixels + i * pixel, *y = b->pixels + i * pixel;
        if (memcmp(x, y, pixel) == 0)
            continue;
        count++;
        for (size_t c = 0; c < pixel; c++) {
            int d = abs((int)x[c] - (int)y[c]);
            *largest = d > *largest ? d : *largest;
        }
    }
    return count;
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    fc_pipeline_destroy(f.pipeline);   /* the fixture's context, this test's pipelines */
    f.pipeline = NULL;
    fc_frame frame;
    fc_image uniform_images[IMAGES] = {0}, flat_images[IMAGES] = {0};
    bool ok = ball(&frame);
    CHECK_MSG(ok, "out of memory");
    ok = ok && render_all(FC_CONSTANTS_UNIFORMS, &frame, uniform_images);
    ok = ok && render_all(FC_CONSTANTS_FLAT, &frame, flat_images);
    int differing = 0;
    for (int k = 0; ok && k < IMAGES; k++) {
        const fc_image *a = &uniform_images[k], *b = &flat_images[k];
        bool same_shape = a->width == b->width && a->height == b->height && fc_image_size(a) == fc_image_size(b);
        CHECK_MSG(same_shape, "image %d: different sizes", k);
        int largest = 0, pixels = same_shape ? differing_pixels(a, b, &largest) : 0;
        differing += pixels > 0;
        CHECK_MSG(pixels == 0, "image %d (%s, camera %d, %s): %d pixels differ, by up to %d in a byte", k,
                  look_names[k / (2 * CAMERAS)], k / 2 % CAMERAS, k % 2 ? "float" : "8-bit", pixels, largest);
    }
    if (ok)
        printf("%d images compared (%d looks x %d cameras, 8-bit and float), %d differ\n", IMAGES, LOOKS, CAMERAS,
               differing);
    for (int k = 0; k < IMAGES; k++) {
        fc_image_free(&uniform_images[k]);
        fc_image_free(&flat_images[k]);
    }
    free(frame.positions);
    free(frame.velocity);
    fixture_close(&f);
    return test_result();
}
