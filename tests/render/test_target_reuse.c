/* test_target_reuse.c — render targets only grow, so a small image is drawn in
 * the lower-left corner of textures that still hold a larger, earlier image.
 * Every pass must read only the image in use: a pipeline that first renders a
 * 640x480 image full of fluid and then a 333x217 image of another scene must
 * produce what a pipeline that never rendered anything larger produces, for
 * every AOV, both splats, and the reduced smoothing and thickness scales (333
 * and 217 are multiples of neither 2 nor 4, so the reduced images have a
 * partial last texel). */
#include <math.h>
#include <stdlib.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

#define LARGE_WIDTH 640
#define LARGE_HEIGHT 480
#define SMALL_WIDTH 333
#define SMALL_HEIGHT 217
#define RADIUS 0.05f

/* Float channels may differ by rounding where a normalised coordinate is
 * divided by a different texture size (bilinear thickness, background);
 * a stale read differs by the depth of another scene. */
#define FLOAT_TOLERANCE 1e-4
#define U8_TOLERANCE 1

typedef struct grid {
    float *positions;
    uint64_t count;
} grid;

/* A jittered layer of particles spaced 1.6 radii apart over [x0, x1] x [y0, y1]
 * around depth z, with a wave (shifted by `phase`) so that the smoothing and
 * normals vary. */
static grid particle_layer(float x0, float x1, float y0, float y1, float z, float phase)
{
    const float spacing = 1.6f * RADIUS;
    uint64_t nx = (uint64_t)((x1 - x0) / spacing) + 1, ny = (uint64_t)((y1 - y0) / spacing) + 1;
    grid g = {malloc(nx * ny * 3 * sizeof(float)), nx * ny};
    if (!g.positions)
        return (grid){0};
    for (uint64_t j = 0; j < ny; j++)
        for (uint64_t i = 0; i < nx; i++) {
            float *p = g.positions + 3 * (j * nx + i);
            p[0] = x0 + spacing * (float)i + 0.2f * spacing * (float)((i * 7 + j * 3) % 5) / 5.0f;
            p[1] = y0 + spacing * (float)j;
            p[2] = z + 0.15f * sinf(3.0f * p[0] + phase) * cosf(2.0f * p[1]);
        }
    return g;
}

typedef struct render_case {
    const char *name;
    fc_aov aov;
    int want_u8;
    fc_smoothing smoothing;
    float smooth_scale;
    float thickness_scale;
    fc_splat_method splat;   /* forced; FC_SPLAT_AUTO where no depth splat runs (reduced thickness only) */
} render_case;

/* Smoothing and thickness scales each ascend, per target: the fresh pipeline
 * meets every size when it is the largest that target has held, so its own
 * targets are exactly the image in use (nothing stale to read). */
static const render_case CASES[] = {
    {"colour u8, curvature flow and thickness at 1/4", FC_AOV_COLOR, 1, FC_SMOOTHING_CURVATURE, 0.25f, 0.25f,
     FC_SPLAT_FRAGMENT},
    {"colour f32, binomial at 1/4", FC_AOV_COLOR, 0, FC_SMOOTHING_BINOMIAL, 0.25f, 0.25f, FC_SPLAT_FRAGMENT},
    {"smoothed depth, narrow range at 1/4", FC_AOV_SMOOTHED_DEPTH, 0, FC_SMOOTHING_NARROW, 0.25f, 0.25f,
     FC_SPLAT_FRAGMENT},
    {"colour u8, bilateral and thickness at 1/2", FC_AOV_COLOR, 1, FC_SMOOTHING_BILATERAL, 0.5f, 0.5f,
     FC_SPLAT_COMPUTE},
    {"thickness at 1/2", FC_AOV_THICKNESS, 0, FC_SMOOTHING_NARROW, 1.0f, 0.5f, FC_SPLAT_AUTO},
    {"smoothed depth, curvature flow at 1/2", FC_AOV_SMOOTHED_DEPTH, 0, FC_SMOOTHING_CURVATURE, 0.5f, 1.0f,
     FC_SPLAT_FRAGMENT},
    {"colour u8, narrow range", FC_AOV_COLOR, 1, FC_SMOOTHING_NARROW, 1.0f, 1.0f, FC_SPLAT_FRAGMENT},
    {"colour f32, compute splat", FC_AOV_COLOR, 0, FC_SMOOTHING_NARROW, 1.0f, 1.0f, FC_SPLAT_COMPUTE},
    {"depth, compute splat", FC_AOV_DEPTH, 0, FC_SMOOTHING_NONE, 1.0f, 1.0f, FC_SPLAT_COMPUTE},
    {"smoothed depth, bilateral", FC_AOV_SMOOTHED_DEPTH, 0, FC_SMOOTHING_BILATERAL, 1.0f, 1.0f, FC_SPLAT_FRAGMENT},
    {"smoothed depth, binomial", FC_AOV_SMOOTHED_DEPTH, 0, FC_SMOOTHING_BINOMIAL, 1.0f, 1.0f, FC_SPLAT_FRAGMENT},
    {"thickness", FC_AOV_THICKNESS, 0, FC_SMOOTHING_NARROW, 1.0f, 1.0f, FC_SPLAT_COMPUTE},
    {"normal", FC_AOV_NORMAL, 0, FC_SMOOTHING_CURVATURE, 1.0f, 1.0f, FC_SPLAT_FRAGMENT},
    {"noise", FC_AOV_NOISE, 0, FC_SMOOTHING_NARROW, 1.0f, 1.0f, FC_SPLAT_FRAGMENT},
};

static fc_settings case_settings(const render_case *c)
{
    fc_settings s = test_settings(RADIUS, c->smoothing, c->smoothing == FC_SMOOTHING_CURVATURE ? 10 : 2);
    s.smooth_scale = c->smooth_scale;
    s.thickness_scale = c->thickness_scale;
    s.thickness_blur = 3;
    s.refraction = 200.0f;   /* shifts that reach past the image's edge: the clamp must hold them inside */
    s.specular = 0.5f;
    s.noise = 0.5f;
    s.foam = 1.0f;
    return s;
}

static fc_code render(fc_pipeline *p, const grid *g, const fc_camera *cam, const fc_settings *s,
                      const render_case *c, fc_image *img)
{
    fc_frame frame = {.count = g->count, .positions = g->positions};
    fc_error err = {0};
    fc_pipeline_force_splat(p, c->splat);
    fc_code code = fc_pipeline_upload(p, &frame, NULL, &err);
    if (code == FC_OK)
        code = fc_pipeline_render(p, cam, s, c->aov, c->want_u8, img, NULL, &err);
    if (code != FC_OK)
        fprintf(stderr, "%s: render failed: %s\n", c->name, err.message);
    return code;
}

/* Largest difference of two images of the same layout, relative to the
 * tolerance of their pixel type (> 1: they differ by more). */
static double difference(const fc_image *a, const fc_image *b)
{
    size_t values = (size_t)a->width * a->height * a->channels;
    double worst = 0.0;
    for (size_t i = 0; i < values; i++) {
        double d;
        if (a->type == FC_PIXEL_U8) {
            d = fabs((double)((const uint8_t *)a->pixels)[i] - ((const uint8_t *)b->pixels)[i]) / U8_TOLERANCE;
        } else {
            double x = ((const float *)a->pixels)[i], y = ((const float *)b->pixels)[i];
            d = fabs(x - y) / (FLOAT_TOLERANCE * fmax(1.0, fabs(y)));
        }
        worst = fmax(worst, d);
    }
    return worst;
}

/* Whether the small image has fluid along its top and right edges, where a
 * read past the image in use would find the large scene. */
static bool fluid_on_edges(const fc_image *depth)
{
    uint32_t top = 0, right = 0;
    for (uint32_t x = 0; x < depth->width; x++)
        top += pixel_f32(depth, x, 0) > 0.0f;
    for (uint32_t row = 0; row < depth->height; row++)
        right += pixel_f32(depth, depth->width - 1, row) > 0.0f;
    return top > depth->width / 4 && right > depth->height / 4;
}

static void check_case(fc_pipeline *reused, fc_pipeline *fresh, const grid *large_scene, const grid *small_scene,
                       const render_case *c)
{
    fc_camera large = axis_camera(3.0, LARGE_WIDTH, LARGE_HEIGHT);
    fc_camera small = axis_camera(3.0, SMALL_WIDTH, SMALL_HEIGHT);
    fc_settings s = case_settings(c);
    fc_image stale = {0}, reused_small = {0}, fresh_small = {0};
    CHECK_CODE(render(reused, large_scene, &large, &s, c, &stale), FC_OK);
    CHECK_CODE(render(reused, small_scene, &small, &s, c, &reused_small), FC_OK);
    CHECK_CODE(render(fresh, small_scene, &small, &s, c, &fresh_small), FC_OK);
    CHECK_MSG(c->splat == FC_SPLAT_AUTO || fc_pipeline_last_splat(reused) == c->splat, "%s: splat not as forced",
              c->name);
    if (reused_small.pixels && fresh_small.pixels) {
        CHECK(reused_small.width == SMALL_WIDTH && reused_small.height == SMALL_HEIGHT);
        CHECK(reused_small.channels == fresh_small.channels && reused_small.type == fresh_small.type);
        double d = difference(&reused_small, &fresh_small);
        CHECK_MSG(d <= 1.0, "%s: after a %dx%d image, differs from a fresh pipeline by %.3g tolerances", c->name,
                  LARGE_WIDTH, LARGE_HEIGHT, d);
    }
    fc_image_free(&stale);
    fc_image_free(&reused_small);
    fc_image_free(&fresh_small);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    fc_pipeline *fresh = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_pipeline_create(&(fc_pipeline_config){0}, &fresh, &err), FC_OK);
    /* The large scene covers the whole 640x480 view; the small one reaches
     * past the top and right of its image. Their waves are out of phase:
     * along the small image's edges the stale depth is sometimes within a
     * particle radius of the surface, where the filters and normals would
     * take it for more of the same surface. */
    grid large_scene = particle_layer(-1.7f, 1.7f, -1.3f, 1.3f, 0.6f, 2.0f);
    grid small_scene = particle_layer(-0.6f, 1.9f, -0.5f, 1.4f, 0.6f, 0.0f);
    CHECK(large_scene.positions && small_scene.positions);
    if (fresh && large_scene.positions && small_scene.positions) {
        fc_image depth = {0};
        fc_camera small = axis_camera(3.0, SMALL_WIDTH, SMALL_HEIGHT);
        fc_settings s = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
        CHECK_CODE(
            render_positions(&f, small_scene.positions, small_scene.count, &small, &s, FC_AOV_DEPTH, 0, &depth),
            FC_OK);
        CHECK_MSG(depth.pixels && fluid_on_edges(&depth), "the small scene must reach the image's edges");
        fc_image_free(&depth);
        for (size_t i = 0; i < sizeof CASES / sizeof CASES[0]; i++)
            check_case(f.pipeline, fresh, &large_scene, &small_scene, &CASES[i]);
    }
    free(large_scene.positions);
    free(small_scene.positions);
    fc_pipeline_destroy(fresh);
    fixture_close(&f);
    return test_result();
}
