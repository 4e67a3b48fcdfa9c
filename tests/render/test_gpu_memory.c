/* test_gpu_memory.c — fc_pipeline_gpu_memory: the particle buffers are sized
 * exactly to the largest frame, the render targets to what their formats
 * imply for the image (the list in pipeline.h), the readback to the largest
 * image read back; rendering again, a smaller frame or a smaller image
 * allocates nothing; a larger image grows the targets; trim frees them. */
#include <stdlib.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

#define PARTICLES 1000
#define WIDTH 96
#define HEIGHT 72   /* no extent a power of two: those get a texel more (test_image_sizes) */

/* fc_particle_buffer positions (3 floats) + fc_particle_record (id, speed) + the noise amplitude. */
#define PARTICLE_BYTES (12 + 8 + 4)

/* Bytes per pixel of every target a full-resolution request can size to the
 * image (smoothing and thickness at scale 1), from the formats in pipeline.h. */
static const uint64_t FULL_RESOLUTION_PIXEL_BYTES =
    3 * 4            /* depth pass: raw, thickness, linear depth, R32F */
    + 2 * 4          /* compute splat: nearest depth and thickness sum, R32UI */
    + 4 / 4          /* thickness blur result, R32F at half the resolution per axis (blur 2 is the
                        resampling alone: no Gaussian pass, so no "across" target) */
    + 2 * 4          /* curvature flow ping-pong, R32F */
    + 2 * 4          /* bilateral ping-pong, R32F */
    + 2 * 4          /* narrow range ping-pong, R32F */
    + 2 * 16         /* binomial ping-pong, RGBA32F */
    + 4              /* noise, R32F */
    + 16             /* normals, RGBA32F */
    + 8              /* background, RGBA16F */
    + (4 + 8)        /* 8-bit composite, SRGB8_ALPHA8 + DEPTH32F_STENCIL8 */
    + (16 + 8);      /* float composite, RGBA32F + DEPTH32F_STENCIL8 */

/* The narrow-range filter's list of the 8x8 blocks that hold fluid
 * (fluid_blocks.h): three workgroup counts and a uint per block of the image. */
#define FLUID_BLOCK_LIST_BYTES(w, h) ((3 + (uint64_t)(((w) + 7) / 8) * (((h) + 7) / 8)) * 4)

/* The pipeline's warm-up renders 8x8 images, in 9x9 textures (fc_gl_non_pot):
 * what it leaves in targets this test does not resize is at most that much of
 * every target. */
#define WARM_UP_PIXELS (9 * 9)

/* A cube of particles spaced two radii apart around the origin. */
static float *particle_cube(uint64_t count)
{
    float *p = malloc(count * 3 * sizeof *p);
    if (!p)
        return NULL;
    for (uint64_t i = 0; i < count; i++) {
        p[3 * i + 0] = 0.1f * (float)(i % 10) - 0.45f;
        p[3 * i + 1] = 0.1f * (float)(i / 10 % 10) - 0.45f;
        p[3 * i + 2] = 0.1f * (float)(i / 100) - 0.45f;
    }
    return p;
}

static fc_code upload(render_fixture *f, const float *positions, uint64_t count)
{
    fc_frame frame = {.count = count, .positions = (float *)positions};
    return fc_pipeline_upload(f->pipeline, &frame, NULL, NULL);
}

static fc_code render(render_fixture *f, const fc_camera *cam, const fc_settings *s, fc_aov aov, int want_u8,
                      fc_image *img)
{
    fc_error err = {0};
    fc_code code = fc_pipeline_render(f->pipeline, cam, s, aov, want_u8, img, NULL, &err);
    if (code != FC_OK)
        fprintf(stderr, "render failed: %s\n", err.message);
    return code;
}

/* Every full-resolution target at the camera's size: each smoothing method,
 * both composites, noise, normals, and the compute splat's images. */
static void render_every_target(render_fixture *f, const fc_camera *cam)
{
    fc_settings s = test_settings(0.05f, FC_SMOOTHING_NONE, 2);
    s.thickness_blur = 2;
    fc_image img = {0};
    const fc_smoothing methods[] = {FC_SMOOTHING_CURVATURE, FC_SMOOTHING_BILATERAL, FC_SMOOTHING_NARROW,
                                    FC_SMOOTHING_BINOMIAL};
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++) {
        s.smoothing = methods[i];
        CHECK_CODE(render(f, cam, &s, FC_AOV_COLOR, 1, &img), FC_OK);
    }
    CHECK_CODE(render(f, cam, &s, FC_AOV_COLOR, 0, &img), FC_OK);
    s.noise = 1.0f;
    CHECK_CODE(render(f, cam, &s, FC_AOV_NOISE, 0, &img), FC_OK);
    CHECK_CODE(render(f, cam, &s, FC_AOV_NORMAL, 0, &img), FC_OK);
    fc_pipeline_force_splat(f->pipeline, FC_SPLAT_COMPUTE);
    CHECK_CODE(render(f, cam, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    CHECK(fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_COMPUTE);
    fc_pipeline_force_splat(f->pipeline, FC_SPLAT_FRAGMENT);
    CHECK_CODE(render(f, cam, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    fc_image_free(&img);
}

static void check_same(const fc_gpu_memory *a, const fc_gpu_memory *b, const char *after)
{
    CHECK_MSG(a->particle_bytes == b->particle_bytes, "%s: particles %llu -> %llu bytes", after,
              (unsigned long long)a->particle_bytes, (unsigned long long)b->particle_bytes);
    CHECK_MSG(a->render_target_bytes == b->render_target_bytes, "%s: render targets %llu -> %llu bytes", after,
              (unsigned long long)a->render_target_bytes, (unsigned long long)b->render_target_bytes);
    CHECK_MSG(a->readback_bytes == b->readback_bytes, "%s: readback %llu -> %llu bytes", after,
              (unsigned long long)a->readback_bytes, (unsigned long long)b->readback_bytes);
    CHECK_MSG(a->allocations == b->allocations, "%s: %llu -> %llu allocations", after,
              (unsigned long long)a->allocations, (unsigned long long)b->allocations);
}

static void test_sizes_and_reuse(render_fixture *f, const float *positions)
{
    CHECK_CODE(upload(f, positions, PARTICLES), FC_OK);
    fc_gpu_memory uploaded;
    fc_pipeline_gpu_memory(f->pipeline, &uploaded);
    CHECK_MSG(uploaded.particle_bytes == (uint64_t)PARTICLES * PARTICLE_BYTES, "particles: %llu bytes",
              (unsigned long long)uploaded.particle_bytes);

    fc_camera cam = axis_camera(3.0, WIDTH, HEIGHT);
    render_every_target(f, &cam);
    fc_gpu_memory first;
    fc_pipeline_gpu_memory(f->pipeline, &first);
    CHECK(first.particle_bytes == uploaded.particle_bytes);
    const uint64_t targets = FULL_RESOLUTION_PIXEL_BYTES * WIDTH * HEIGHT + FLUID_BLOCK_LIST_BYTES(WIDTH, HEIGHT);
    CHECK_MSG(first.render_target_bytes >= targets &&
                  first.render_target_bytes <= targets + FULL_RESOLUTION_PIXEL_BYTES * WARM_UP_PIXELS,
              "render targets: %llu bytes, the formats imply %llu", (unsigned long long)first.render_target_bytes,
              (unsigned long long)targets);
    /* The largest image read back: RGBA float colour. */
    CHECK_MSG(first.readback_bytes == (uint64_t)WIDTH * HEIGHT * 16, "readback: %llu bytes",
              (unsigned long long)first.readback_bytes);
    CHECK(fc_gpu_memory_total(&first) == first.particle_bytes + first.render_target_bytes + first.readback_bytes);

    render_every_target(f, &cam);
    fc_gpu_memory again;
    fc_pipeline_gpu_memory(f->pipeline, &again);
    check_same(&first, &again, "the same requests again");

    /* A smaller frame keeps the buffers of the larger one. */
    CHECK_CODE(upload(f, positions, PARTICLES / 2), FC_OK);
    render_every_target(f, &cam);
    fc_gpu_memory smaller_frame;
    fc_pipeline_gpu_memory(f->pipeline, &smaller_frame);
    check_same(&first, &smaller_frame, "a smaller frame");
}

/* Targets only grow, per axis: a smaller image allocates nothing and keeps
 * the bytes; one larger along an axis grows the targets its stages use to the
 * larger of the two sizes on each axis; trim gives every target back, and the
 * next render allocates only what it uses, at its size. The readback buffer
 * and the particles are not touched. */
static void test_image_sizes(render_fixture *f, const float *positions)
{
    CHECK_CODE(upload(f, positions, PARTICLES), FC_OK);
    fc_camera cam = axis_camera(3.0, WIDTH, HEIGHT);
    fc_settings s = test_settings(0.05f, FC_SMOOTHING_NONE, 0);
    fc_image img = {0};
    CHECK_CODE(render(f, &cam, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    fc_gpu_memory before;
    fc_pipeline_gpu_memory(f->pipeline, &before);

    fc_camera small = axis_camera(3.0, WIDTH / 2, HEIGHT / 2);
    CHECK_CODE(render(f, &small, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    CHECK(img.width == WIDTH / 2 && img.height == HEIGHT / 2);
    fc_gpu_memory smaller;
    fc_pipeline_gpu_memory(f->pipeline, &smaller);
    check_same(&before, &smaller, "a smaller image");
    CHECK_CODE(render(f, &cam, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    fc_gpu_memory back;
    fc_pipeline_gpu_memory(f->pipeline, &back);
    check_same(&before, &back, "the larger image after the smaller one");

    /* Narrower but taller: the raw depth needs the depth pass's three R32F
     * targets, which grow to WIDTH x TALL (not WIDTH / 2 x TALL). */
    const uint32_t tall = HEIGHT + 16;
    fc_camera taller = axis_camera(3.0, WIDTH / 2, tall);
    CHECK_CODE(render(f, &taller, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    fc_gpu_memory grown;
    fc_pipeline_gpu_memory(f->pipeline, &grown);
    const uint64_t growth = 3 * 4 * (uint64_t)WIDTH * (tall - HEIGHT);
    CHECK_MSG(grown.render_target_bytes - before.render_target_bytes == growth, "render targets %llu -> %llu",
              (unsigned long long)before.render_target_bytes, (unsigned long long)grown.render_target_bytes);
    CHECK(grown.allocations == before.allocations + 3);
    CHECK(grown.readback_bytes == before.readback_bytes && grown.particle_bytes == before.particle_bytes);

    fc_pipeline_trim(f->pipeline);
    fc_gpu_memory trimmed;
    fc_pipeline_gpu_memory(f->pipeline, &trimmed);
    CHECK_MSG(trimmed.render_target_bytes == 0, "after trim: render targets %llu bytes",
              (unsigned long long)trimmed.render_target_bytes);
    CHECK(trimmed.allocations == grown.allocations);
    CHECK(trimmed.readback_bytes == grown.readback_bytes && trimmed.particle_bytes == grown.particle_bytes);

    CHECK_CODE(render(f, &small, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    fc_gpu_memory after_trim;
    fc_pipeline_gpu_memory(f->pipeline, &after_trim);
    CHECK_MSG(after_trim.render_target_bytes == 3 * 4 * (uint64_t)(WIDTH / 2) * (HEIGHT / 2),
              "after trim and a small image: render targets %llu bytes",
              (unsigned long long)after_trim.render_target_bytes);
    CHECK(after_trim.allocations == trimmed.allocations + 3);

    /* An extent that is a power of two gets a texel more (llvmpipe compiles a
     * shader variant per texture for whether its extents are powers of two,
     * gl_util.h): 64 x 32 allocates 65 x 33, 1 x 1 allocates 3 x 3. */
    fc_pipeline_trim(f->pipeline);
    fc_camera pot = axis_camera(3.0, 64, 32);
    CHECK_CODE(render(f, &pot, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    fc_gpu_memory padded;
    fc_pipeline_gpu_memory(f->pipeline, &padded);
    CHECK_MSG(padded.render_target_bytes == 3 * 4 * 65 * 33, "a 64x32 image: render targets %llu bytes",
              (unsigned long long)padded.render_target_bytes);
    fc_pipeline_trim(f->pipeline);
    fc_camera one = axis_camera(3.0, 1, 1);
    CHECK_CODE(render(f, &one, &s, FC_AOV_DEPTH, 0, &img), FC_OK);
    fc_pipeline_gpu_memory(f->pipeline, &padded);
    CHECK_MSG(padded.render_target_bytes == 3 * 4 * 3 * 3, "a 1x1 image: render targets %llu bytes",
              (unsigned long long)padded.render_target_bytes);
    fc_image_free(&img);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    float *positions = particle_cube(PARTICLES);
    CHECK(positions != NULL);
    if (positions) {
        test_sizes_and_reuse(&f, positions);
        test_image_sizes(&f, positions);
    }
    free(positions);
    fixture_close(&f);
    return test_result();
}
