/* test_shading_compositing.c — the composite against analytic values: at
 * normal incidence the fluid reflects F0 = ((ior-1)/(ior+1))² of a uniform
 * client cube map over a black client background; a client background image
 * fills the view where there is no fluid, upright and cover-fitted; scene
 * textures reject malformed images with the right codes. */
#include <math.h>
#include <string.h>

#include "shading_fixture.h"
#include "test_util.h"

#define SIZE 33   /* odd: pixel 16 sits on the view axis */

static const float SKY[3] = {0.5f, 1.0f, 2.0f};   /* distinct per channel, beyond 1 in one */

static void fill_f32(fc_image *img, float *pixels, uint32_t size, const float rgb[3])
{
    for (uint32_t i = 0; i < size * size; i++)
        memcpy(pixels + 3 * i, rgb, 3 * sizeof(float));
    *img = (fc_image){.width = size, .height = size, .channels = 3, .type = FC_PIXEL_F32, .pixels = pixels};
}

/* A uniform cube map of colour SKY and a black background image. */
static fc_scene_textures *uniform_scene(render_fixture *f)
{
    static float face_pixels[6][4 * 4 * 3], black_pixels[2 * 2 * 3];
    const float black[3] = {0.0f, 0.0f, 0.0f};
    fc_image faces[6], background;
    for (int i = 0; i < 6; i++)
        fill_f32(&faces[i], face_pixels[i], 4, SKY);
    fill_f32(&background, black_pixels, 2, black);
    fc_scene_textures *scene = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_scene_textures_create(f->pipeline, &background, faces, &scene, &err), FC_OK);
    return scene;
}

/* One large sphere seen head-on: at the centre pixel its normal faces the
 * camera; with no absorption the refracted part is the black background, so
 * the colour is F0 times the cube map's colour. */
static void check_fresnel_f0(render_fixture *f, const fc_scene_textures *scene, float ior)
{
    const float centre[3] = {0.0f, 0.0f, 0.0f};
    fc_frame frame = {.count = 1, .positions = (float *)centre};
    fc_camera cam = axis_camera(5.0, SIZE, SIZE);
    fc_settings settings = test_settings(1.0f, FC_SMOOTHING_NONE, 0);
    settings.absorption[0] = settings.absorption[1] = settings.absorption[2] = 0.0f;
    settings.ior = ior;
    settings.refraction = 20.0f;   /* irrelevant over a uniform background */
    fc_image img = {0};
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, scene, FC_AOV_COLOR, 0, &img), FC_OK);
    double f0 = pow((ior - 1.0) / (ior + 1.0), 2.0);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(channel_f32(&img, 16, 16, c), f0 * SKY[c], 1e-3 * f0 * SKY[c]);
        CHECK(channel_f32(&img, 0, 0, c) == 0.0f);   /* the black background beside the sphere */
    }
    fc_image_free(&img);
}

static void test_fresnel_at_normal_incidence(render_fixture *f)
{
    fc_scene_textures *scene = uniform_scene(f);
    if (!scene)
        return;
    check_fresnel_f0(f, scene, 1.33f);
    check_fresnel_f0(f, scene, 1.5f);
    fc_scene_textures_destroy(scene);
}

/* Specular adds k_s (n·h)^α times the sun's highlight radiance (4 x its
 * colour, composite.frag.glsl) on top: at the centre n = v, so with the sun
 * behind the camera's shoulder the highlight is positive but below that
 * peak, and coloured like the sun. */
static void test_specular_adds_light(render_fixture *f)
{
    fc_scene_textures *scene = uniform_scene(f);
    if (!scene)
        return;
    const float centre[3] = {0.0f, 0.0f, 0.0f};
    fc_frame frame = {.count = 1, .positions = (float *)centre};
    fc_camera cam = axis_camera(5.0, SIZE, SIZE);
    fc_settings settings = test_settings(1.0f, FC_SMOOTHING_NONE, 0);
    settings.absorption[0] = settings.absorption[1] = settings.absorption[2] = 0.0f;
    fc_image plain = {0}, lit = {0};
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, scene, FC_AOV_COLOR, 0, &plain), FC_OK);
    settings.specular = 0.5f;
    settings.shininess = 4.0f;
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, scene, FC_AOV_COLOR, 0, &lit), FC_OK);
    const double sun_color[3] = {1.00, 0.93, 0.82}, peak = 4.0 * 0.5;
    double highlight = channel_f32(&lit, 16, 16, 0) - channel_f32(&plain, 16, 16, 0);
    CHECK_MSG(highlight > 0.01 && highlight < peak, "highlight %g", highlight);
    for (int c = 1; c < 3; c++)
        CHECK_NEAR(channel_f32(&lit, 16, 16, c) - channel_f32(&plain, 16, 16, c), highlight * sun_color[c], 1e-4);
    fc_image_free(&plain);
    fc_image_free(&lit);
    fc_scene_textures_destroy(scene);
}

/* A 4x2 image in four quadrants: red, blue on top; green, white below. */
static const uint8_t QUADRANTS[2][4][4] = {
    {{255, 0, 0, 255}, {255, 0, 0, 255}, {0, 0, 255, 255}, {0, 0, 255, 255}},
    {{0, 255, 0, 255}, {0, 255, 0, 255}, {255, 255, 255, 255}, {255, 255, 255, 255}},
};

static void check_quadrant(const fc_image *img, uint32_t x, uint32_t row, const uint8_t *rgba)
{
    for (int c = 0; c < 3; c++)
        CHECK_MSG(channel_u8(img, x, row, c) == rgba[c], "pixel (%u, %u) channel %d: %u, expected %u", x, row, c,
                  channel_u8(img, x, row, c), rgba[c]);
}

/* Particles far outside the view: the image is background only. */
static void test_client_background(render_fixture *f)
{
    fc_image background = {.width = 4, .height = 2, .channels = 4, .type = FC_PIXEL_U8,
                           .pixels = (void *)QUADRANTS};
    fc_scene_textures *scene = NULL;
    CHECK_CODE(fc_scene_textures_create(f->pipeline, &background, NULL, &scene, NULL), FC_OK);
    if (!scene)
        return;
    const float away[3] = {100.0f, 0.0f, 0.0f};
    fc_frame frame = {.count = 1, .positions = (float *)away};
    fc_settings settings = test_settings(0.5f, FC_SMOOTHING_NONE, 0);
    fc_image img = {0};
    /* Same aspect as the image: it fills the view exactly. */
    fc_camera wide = axis_camera(4.0, 64, 32);
    CHECK_CODE(render_frame(f, &frame, &wide, &settings, scene, FC_AOV_COLOR, 1, &img), FC_OK);
    check_quadrant(&img, 8, 4, QUADRANTS[0][0]);
    check_quadrant(&img, 56, 4, QUADRANTS[0][3]);
    check_quadrant(&img, 8, 28, QUADRANTS[1][0]);
    check_quadrant(&img, 56, 28, QUADRANTS[1][3]);
    /* A square view shows the image's middle half across, undistorted: the
     * quadrants still meet in the centre and the outer columns are cropped. */
    fc_camera square = axis_camera(4.0, 32, 32);
    CHECK_CODE(render_frame(f, &frame, &square, &settings, scene, FC_AOV_COLOR, 1, &img), FC_OK);
    check_quadrant(&img, 4, 4, QUADRANTS[0][0]);
    check_quadrant(&img, 28, 4, QUADRANTS[0][3]);
    check_quadrant(&img, 4, 28, QUADRANTS[1][0]);
    check_quadrant(&img, 28, 28, QUADRANTS[1][3]);
    fc_image_free(&img);
    fc_scene_textures_destroy(scene);
}

static void test_malformed_scene_textures(render_fixture *f)
{
    float pixels[4 * 2 * 4] = {0};
    fc_scene_textures *scene = (fc_scene_textures *)pixels;   /* must be reset to NULL */
    fc_error err = {0};
    fc_image two_channels = {.width = 4, .height = 2, .channels = 2, .type = FC_PIXEL_F32, .pixels = pixels};
    CHECK_CODE(fc_scene_textures_create(f->pipeline, &two_channels, NULL, &scene, &err), FC_ERR_INVALID_VALUE);
    CHECK(scene == NULL);
    CHECK(strstr(err.message, "channels") != NULL);

    fc_image faces[6];
    for (int i = 0; i < 6; i++)
        faces[i] = (fc_image){.width = 2, .height = 2, .channels = 4, .type = FC_PIXEL_F32, .pixels = pixels};
    faces[3].width = 4;
    CHECK_CODE(fc_scene_textures_create(f->pipeline, NULL, faces, &scene, &err), FC_ERR_INVALID_VALUE);
    CHECK(strstr(err.message, "face 3") != NULL);
    faces[3].width = 2;
    faces[5].type = FC_PIXEL_U8;
    CHECK_CODE(fc_scene_textures_create(f->pipeline, NULL, faces, &scene, &err), FC_ERR_INVALID_VALUE);

    fc_image huge = {.width = 1u << 20, .height = 1, .channels = 4, .type = FC_PIXEL_F32, .pixels = pixels};
    CHECK_CODE(fc_scene_textures_create(f->pipeline, &huge, NULL, &scene, &err), FC_ERR_LIMIT);
    CHECK_CODE(fc_scene_textures_create(NULL, NULL, NULL, &scene, &err), FC_ERR_USAGE);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_fresnel_at_normal_incidence(&f);
    test_specular_adds_light(&f);
    test_client_background(&f);
    test_malformed_scene_textures(&f);
    fixture_close(&f);
    return test_result();
}
