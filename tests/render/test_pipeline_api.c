/* test_pipeline_api.c — the pipeline.h contract around the passes: request
 * checks and their codes, which stages report timings, image reuse, an empty
 * frame, and shaders loaded from a directory instead of the binary. */
#include <string.h>

#include "render_fixture.h"
#include "test_util.h"

static const float ONE_PARTICLE[3] = {0.0f, 0.0f, 0.0f};

static fc_code upload_one(fc_pipeline *p, float *upload_ms)
{
    fc_frame frame = {.count = 1, .positions = (float *)ONE_PARTICLE};
    return fc_pipeline_upload(p, &frame, upload_ms, NULL);
}

static void test_render_before_upload(render_fixture *f)
{
    /* A fresh pipeline: the fixture's has not been given a frame yet. */
    fc_camera cam = axis_camera(4.0, 16, 16);
    fc_settings settings = test_settings(0.5f, FC_SMOOTHING_NONE, 0);
    fc_image img = {0};
    fc_error err = {0};
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_COLOR, 1, &img, NULL, &err),
               FC_ERR_BAD_STATE);
    CHECK(strlen(err.message) > 0);
}

static void test_invalid_requests(render_fixture *f)
{
    CHECK_CODE(upload_one(f->pipeline, NULL), FC_OK);
    fc_camera cam = axis_camera(4.0, 16, 16);
    fc_settings settings = test_settings(0.5f, FC_SMOOTHING_NONE, 0);
    fc_image img = {0};
    fc_error err = {0};

    fc_settings auto_radius = settings;
    auto_radius.radius = 0.0f;
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &auto_radius, FC_AOV_COLOR, 1, &img, NULL, &err),
               FC_ERR_INVALID_VALUE);
    CHECK(strstr(err.message, "radius") != NULL);

    fc_camera no_fov = cam;
    no_fov.fov_y_deg = 0.0f;
    CHECK_CODE(fc_pipeline_render(f->pipeline, &no_fov, &settings, FC_AOV_COLOR, 1, &img, NULL, &err),
               FC_ERR_INVALID_VALUE);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, (fc_aov)7, 1, &img, NULL, &err),
               FC_ERR_INVALID_VALUE);

    fc_camera huge = cam;
    huge.width = 1u << 20;
    CHECK_CODE(fc_pipeline_render(f->pipeline, &huge, &settings, FC_AOV_COLOR, 1, &img, NULL, &err),
               FC_ERR_RENDER);
    CHECK(strstr(err.message, "1048576") != NULL);
    fc_image_free(&img);
}

static void test_stage_timings(render_fixture *f)
{
    float upload_ms = -1.0f, ms[FC_STAGE_COUNT];
    CHECK_CODE(upload_one(f->pipeline, &upload_ms), FC_OK);
    CHECK(upload_ms >= 0.0f);
    fc_camera cam = axis_camera(4.0, 32, 32);
    fc_settings settings = test_settings(0.5f, FC_SMOOTHING_CURVATURE, 3);
    fc_image img = {0};

    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_COLOR, 1, &img, ms, NULL), FC_OK);
    const fc_stage ran[] = {FC_STAGE_DEPTH, FC_STAGE_THICKNESS, FC_STAGE_SMOOTHING, FC_STAGE_COMPOSITE,
                            FC_STAGE_READBACK};
    for (size_t i = 0; i < sizeof ran / sizeof ran[0]; i++)
        CHECK_MSG(ms[ran[i]] >= 0.0f && ms[ran[i]] < 60000.0f, "stage %d: %g ms", (int)ran[i], ms[ran[i]]);
    /* Not the pipeline's stages: the daemon measures them. */
    CHECK(ms[FC_STAGE_UPLOAD] < 0.0f && ms[FC_STAGE_ENCODE] < 0.0f && ms[FC_STAGE_TOTAL] < 0.0f);

    /* The raw depth needs nothing after the depth pass. */
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_DEPTH, 0, &img, ms, NULL), FC_OK);
    CHECK(ms[FC_STAGE_DEPTH] >= 0.0f && ms[FC_STAGE_READBACK] >= 0.0f);
    CHECK(ms[FC_STAGE_THICKNESS] < 0.0f && ms[FC_STAGE_SMOOTHING] < 0.0f && ms[FC_STAGE_COMPOSITE] < 0.0f);

    settings.smoothing = FC_SMOOTHING_NONE;
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_COLOR, 1, &img, ms, NULL), FC_OK);
    CHECK(ms[FC_STAGE_SMOOTHING] < 0.0f && ms[FC_STAGE_COMPOSITE] >= 0.0f);
    fc_image_free(&img);
}

/* Without smoothing the smoothed depth is the raw depth, bit for bit; the
 * image buffer is reused, not regrown, for a smaller request. */
static void test_unsmoothed_depth_and_reuse(render_fixture *f)
{
    CHECK_CODE(upload_one(f->pipeline, NULL), FC_OK);
    fc_camera cam = axis_camera(4.0, 40, 30);
    fc_settings settings = test_settings(0.5f, FC_SMOOTHING_NONE, 0);
    fc_image raw = {0}, smoothed = {0};
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_DEPTH, 0, &raw, NULL, NULL), FC_OK);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_SMOOTHED_DEPTH, 0, &smoothed, NULL, NULL),
               FC_OK);
    CHECK(fc_image_size(&raw) == 40 * 30 * sizeof(float));
    CHECK(memcmp(raw.pixels, smoothed.pixels, fc_image_size(&raw)) == 0);

    void *buffer = raw.pixels;
    size_t capacity = raw.capacity;
    cam.width = 20;
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_DEPTH, 0, &raw, NULL, NULL), FC_OK);
    CHECK(raw.pixels == buffer && raw.capacity == capacity && raw.width == 20);
    fc_image_free(&raw);
    fc_image_free(&smoothed);
}

static void test_empty_frame(render_fixture *f)
{
    fc_frame empty = {0};
    CHECK_CODE(fc_pipeline_upload(f->pipeline, &empty, NULL, NULL), FC_OK);
    fc_camera cam = axis_camera(4.0, 24, 24);
    fc_settings settings = test_settings(0.5f, FC_SMOOTHING_CURVATURE, 5);
    fc_image img = {0};
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_DEPTH, 0, &img, NULL, NULL), FC_OK);
    int fluid = 0;
    for (uint32_t i = 0; i < 24 * 24; i++)
        fluid += ((const float *)img.pixels)[i] != 0.0f;
    CHECK(fluid == 0);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_COLOR, 1, &img, NULL, NULL), FC_OK);
    fc_image_free(&img);
}

/* Shaders from the source directory give the same image as the built-in
 * copies; a directory without them fails naming the missing file. */
static void test_shader_dir(render_fixture *f)
{
    fc_pipeline *from_disk = NULL;
    fc_error err = {0};
    fc_pipeline_config config = {.shader_dir = FC_SHADER_SOURCE_DIR};
    CHECK_CODE(fc_pipeline_create(&config, &from_disk, &err), FC_OK);
    if (from_disk) {
        fc_camera cam = axis_camera(4.0, 32, 32);
        fc_settings settings = test_settings(0.5f, FC_SMOOTHING_CURVATURE, 3);
        fc_image builtin = {0}, disk = {0};
        CHECK_CODE(upload_one(f->pipeline, NULL), FC_OK);
        CHECK_CODE(upload_one(from_disk, NULL), FC_OK);
        CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_COLOR, 1, &builtin, NULL, NULL), FC_OK);
        CHECK_CODE(fc_pipeline_render(from_disk, &cam, &settings, FC_AOV_COLOR, 1, &disk, NULL, NULL), FC_OK);
        CHECK(memcmp(builtin.pixels, disk.pixels, fc_image_size(&builtin)) == 0);
        fc_image_free(&builtin);
        fc_image_free(&disk);
        fc_pipeline_destroy(from_disk);
    }

    fc_pipeline *broken = (fc_pipeline *)&config;   /* must be reset to NULL */
    config.shader_dir = "/nonexistent-fluidcast-shaders";
    CHECK_CODE(fc_pipeline_create(&config, &broken, &err), FC_ERR_GL);
    CHECK(broken == NULL);
    CHECK_MSG(strstr(err.message, ".glsl") != NULL, "message: %s", err.message);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_render_before_upload(&f);
    test_invalid_requests(&f);
    test_stage_timings(&f);
    test_unsmoothed_depth_and_reuse(&f);
    test_empty_frame(&f);
    test_shader_dir(&f);
    fixture_close(&f);
    return test_result();
}
