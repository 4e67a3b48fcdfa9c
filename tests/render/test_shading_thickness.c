/* test_shading_thickness.c — thickness at reduced resolution and blurred:
 * stacked spheres add up to k diameters at full and half resolution, and to
 * the analytic value at the sampled texels at ¼; the Gaussian blur conserves the total and
 * lowers the peak; the floor cuts the chords off exactly where the analytic
 * ray leaves the half-space above it in both surface splats, and in the
 * compute splat of the thickness alone takes the share of the sphere's
 * volume above it. Run with "fragment" and "compute" (depth_pass.h). */
#include <math.h>
#include <stdlib.h>

#include "depth_pass.h"
#include "particle_buffer.h"
#include "shading_fixture.h"
#include "test_util.h"
#include "thickness_filter.h"
#include "thickness_pass.h"

#define SIZE 65        /* odd: pixel 32 sits on the view axis */
#define RADIUS 0.5
#define DISTANCE 4.0
#define SPACING 1.2    /* between stacked centres: the spheres do not touch */

static fc_code render_stack(render_fixture *f, int count, float scale, uint32_t blur, fc_image *out)
{
    float positions[3 * 4] = {0};
    for (int i = 0; i < count; i++)
        positions[3 * i + 2] = (float)(-SPACING * i);
    fc_camera cam = axis_camera(DISTANCE, SIZE, SIZE);
    fc_settings settings = test_settings((float)RADIUS, FC_SMOOTHING_NONE, 0);
    settings.thickness_scale = scale;
    settings.thickness_blur = blur;
    return render_positions(f, positions, (uint64_t)count, &cam, &settings, FC_AOV_THICKNESS, 0, out);
}

/* What the image centre should hold at `scale`: the pass renders a
 * lround(SIZE·scale)-pixel image and samples it bilinearly, so the centre is
 * the mean of the analytic thickness (each sphere's chord) at the one or four
 * texels around the view axis. */
static double expected_centre(int count, float scale)
{
    uint32_t size = (uint32_t)lround(SIZE * scale);
    fc_camera reduced = axis_camera(DISTANCE, size, size);
    /* The texels around the axis: one for odd sizes, two per axis for even. */
    const uint32_t texels[2] = {(size - 1) / 2, size / 2};
    int taps = texels[0] == texels[1] ? 1 : 2;
    double sum = 0.0;
    for (int r = 0; r < taps; r++)
        for (int c = 0; c < taps; c++)
            for (int i = 0; i < count; i++) {
                const double centre[3] = {0.0, 0.0, -SPACING * i};
                double edge;
                analytic_sphere_depth(&reduced, centre, RADIUS, texels[c], texels[r], &edge);
                sum += 2.0 * RADIUS * sqrt(fmax(edge, 0.0));
            }
    return sum / (taps * taps);
}

static void test_stacks_at_each_scale(render_fixture *f)
{
    const float scales[] = {1.0f, 0.5f, 0.25f};
    fc_image img = {0};
    for (int s = 0; s < 3; s++)
        for (int k = 1; k <= 3; k++) {
            CHECK_CODE(render_stack(f, k, scales[s], 0, &img), FC_OK);
            CHECK(img.width == SIZE && img.height == SIZE && img.channels == 1);
            double expected = expected_centre(k, scales[s]);
            CHECK_MSG(fabs(pixel_f32(&img, 32, 32) - expected) <= 1e-4 * expected,
                      "scale %g, %d spheres: %g at the centre, expected %g", scales[s], k, pixel_f32(&img, 32, 32),
                      expected);
            CHECK(pixel_f32(&img, 0, 0) == 0.0f);
        }
    /* Full and half resolution sample the axis itself: k diameters. */
    CHECK_NEAR(expected_centre(3, 1.0f), 3 * 2.0 * RADIUS, 1e-9);
    CHECK_NEAR(expected_centre(3, 0.5f), 3 * 2.0 * RADIUS, 1e-9);
    fc_image_free(&img);
}

static void test_blur_conserves_thickness(render_fixture *f)
{
    fc_image sharp = {0}, blurred = {0}, coarse = {0};
    CHECK_CODE(render_stack(f, 2, 1.0f, 0, &sharp), FC_OK);
    CHECK_CODE(render_stack(f, 2, 1.0f, 6, &blurred), FC_OK);
    CHECK_CODE(render_stack(f, 2, 0.5f, 6, &coarse), FC_OK);
    double total = image_sum(&sharp);
    /* The blur runs at half resolution, and SIZE (odd) pixels are not
     * exactly two per blur texel: the resampling there and back conserves
     * the total to within 1% (exactly at even sizes, test_half_resolution_sums_chords). */
    CHECK_NEAR(image_sum(&blurred), total, 0.01 * total);
    CHECK_NEAR(image_sum(&coarse), total, 0.01 * total);
    /* The peak spreads out: lower at the centre, non-zero past the silhouette. */
    CHECK(pixel_f32(&blurred, 32, 32) < pixel_f32(&sharp, 32, 32) - 1e-3);
    int widened = 0;
    for (uint32_t x = 0; x < SIZE; x++)
        widened += pixel_f32(&sharp, x, 32) == 0.0f && pixel_f32(&blurred, x, 32) > 0.0f;
    CHECK_MSG(widened >= 4, "%d pixels of row 32 gained thickness", widened);
    fc_image_free(&sharp);
    fc_image_free(&blurred);
    fc_image_free(&coarse);
}

/* The length of the ray through pixel (x, row) inside the sphere and above
 * the view-space plane dot(n, p) + w > 0, in double precision. */
static double analytic_clipped_chord(const fc_camera *cam, const double centre[3], double radius,
                                     const double plane[4], uint32_t x, uint32_t row)
{
    double fy = 1.0 / tan(cam->fov_y_deg * 3.14159265358979323846 / 360.0);
    double fx = fy * cam->height / cam->width;
    /* View space of an axis camera is world space shifted by the eye; the
     * image's row 0 is its top. */
    double d[3] = {((x + 0.5) / cam->width * 2.0 - 1.0) / fx, (1.0 - (row + 0.5) / cam->height * 2.0) / fy, -1.0};
    double c[3] = {centre[0], centre[1], centre[2] - cam->eye[2]};
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double dc = d[0] * c[0] + d[1] * c[1] + d[2] * c[2];
    double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    double disc = dc * dc - dd * (cc - radius * radius);
    if (disc <= 0.0)
        return 0.0;
    double t0 = (dc - sqrt(disc)) / dd, t1 = (dc + sqrt(disc)) / dd;
    double rate = plane[0] * d[0] + plane[1] * d[1] + plane[2] * d[2];
    if (rate < 0.0)
        t1 = fmin(t1, -plane[3] / rate);
    else if (rate > 0.0)
        t0 = fmax(t0, -plane[3] / rate);
    return t1 > t0 ? (t1 - t0) * sqrt(dd) : 0.0;
}

/* Filter input: `value(x, y)` at the centre of every texel of a
 * width x height R32F target, y counted from the bottom row as GL does. */
static void fill_target(fc_render_target *t, uint32_t width, uint32_t height, double (*value)(double x, double y))
{
    fc_error err = {0};
    CHECK_CODE(fc_render_target_resize(t, width, height, &err), FC_OK);
    float *texels = malloc(sizeof *texels * width * height);
    CHECK(texels != NULL);
    if (!texels)
        return;
    for (uint32_t y = 0; y < height; y++)
        for (uint32_t x = 0; x < width; x++)
            texels[y * width + x] = (float)value(x + 0.5, y + 0.5);
    glTextureSubImage2D(t->color, 0, 0, 0, (GLsizei)width, (GLsizei)height, GL_RED, GL_FLOAT, texels);
    free(texels);
}

#define FILTER_SOURCE 64   /* pixels per side of the filter tests' source; the blur's are half */
#define FILTER_SIGMA 1.2f  /* blur texels: a kernel of 9 taps, merged into 5 along y */

static double constant(double x, double y)
{
    (void)x, (void)y;
    return 0.75;
}

/* Symmetric about the image's centre, so the row order of a read-back image does not matter. */
static double parabola(double x, double y)
{
    (void)x;
    double d = y - 0.5 * FILTER_SOURCE;
    return d * d;
}

/* The filter downsampling 64 x 64 to 32 x 32 and blurring: a constant stays
 * that constant up to the edges (normalised weights, clamped taps; to 1e-5,
 * as a tap clamped to the image's last texel centre is not exact in texture
 * coordinates of a texture one texel wider, fc_gl_non_pot, and takes a
 * few millionths of the texel beyond);
 * a parabola p(y) = d² gains exactly the kernel's variance, analytic from its
 * definition: averaging rows 2j and 2j + 1 gives 4e² + 1/4 (e the blur
 * texel's centre, in its own units, from the image's), and the Gaussian of
 * weights w_i ∝ exp(-i²/2σ²), |i| <= ceil(3σ), adds 4·Σ w_i·i². A tap
 * offset or weight wrong by a texel fraction shows there. */
static void test_filter_downsamples_and_blurs(void)
{
    fc_thickness_filter filter;
    fc_render_target source = fc_render_target_init(GL_R32F, false, true);
    fc_error err = {0};
    CHECK_CODE(fc_thickness_filter_create(NULL, &filter, &err), FC_OK);
    const uint32_t half = FILTER_SOURCE / 2;
    const fc_render_target *result = NULL;
    fc_image img = {0};

    fill_target(&source, FILTER_SOURCE, FILTER_SOURCE, constant);
    CHECK_CODE(fc_thickness_filter_run(&filter, &source, FILTER_SIGMA, half, half, &result, &err), FC_OK);
    CHECK_CODE(read_target(result, 1, &img, &err), FC_OK);
    CHECK(img.width == half && img.height == half);
    int off = 0;
    for (uint32_t row = 0; row < half; row++)
        for (uint32_t x = 0; x < half; x++)
            off += fabs(pixel_f32(&img, x, row) - 0.75) > 1e-5;
    CHECK_MSG(off == 0, "%d texels of a constant changed", off);

    double weights = 0.0, moment = 0.0;
    int r = (int)ceil(3.0 * FILTER_SIGMA - 1e-3);
    for (int i = -r; i <= r; i++) {
        double w = exp(-0.5 * i * i / ((double)FILTER_SIGMA * FILTER_SIGMA));
        weights += w;
        moment += w * i * i;
    }
    fill_target(&source, FILTER_SOURCE, FILTER_SOURCE, parabola);
    CHECK_CODE(fc_thickness_filter_run(&filter, &source, FILTER_SIGMA, half, half, &result, &err), FC_OK);
    CHECK_CODE(read_target(result, 1, &img, &err), FC_OK);
    /* Rows a kernel away from the edges, near the centre where the parabola
     * is flat enough that bilinear weight rounding stays below 1%. */
    for (uint32_t row = half / 2 - 3; row < half / 2 + 3; row++) {
        double e = row + 0.5 - 0.5 * half;
        double expected = 4.0 * e * e + 0.25 + 4.0 * moment / weights;
        CHECK_MSG(fabs(pixel_f32(&img, 5, row) - expected) <= 0.01 * 4.0 * moment / weights,
                  "row %u: %g, expected %g", row, pixel_f32(&img, 5, row), expected);
    }
    fc_image_free(&img);
    fc_render_target_release(&source);
    fc_thickness_filter_destroy(&filter);
}

/* At the default blur radius (2, which the resampling alone provides) one
 * sphere's thickness image of an even size, blurred at half resolution and
 * read back at the view's size, sums to the analytic chords of its pixels:
 * averaging 2 x 2 pixels and bilinear upsampling both conserve the total. */
static void test_half_resolution_sums_chords(render_fixture *f)
{
    enum { EVEN = 64 };
    const float origin[3] = {0.0f, 0.0f, 0.0f};
    fc_camera cam = axis_camera(DISTANCE, EVEN, EVEN);
    fc_settings settings = test_settings((float)RADIUS, FC_SMOOTHING_NONE, 0);
    settings.thickness_blur = 2;
    fc_image img = {0};
    CHECK_CODE(render_positions(f, origin, 1, &cam, &settings, FC_AOV_THICKNESS, 0, &img), FC_OK);
    CHECK(img.width == EVEN && img.height == EVEN);
    const double centre[3] = {0.0, 0.0, 0.0}, no_plane[4] = {0.0, 0.0, 0.0, 1.0};
    double analytic = 0.0;
    for (uint32_t row = 0; row < EVEN; row++)
        for (uint32_t x = 0; x < EVEN; x++)
            analytic += analytic_clipped_chord(&cam, centre, RADIUS, no_plane, x, row);
    CHECK_MSG(fabs(image_sum(&img) - analytic) <= 1e-3 * analytic, "sum %g, analytic %g", image_sum(&img),
              analytic);
    /* Blurred, yet at most a pixel's worth: the centre keeps nearly 2r. */
    CHECK(pixel_f32(&img, 32, 32) < 2.0 * RADIUS && pixel_f32(&img, 32, 32) > 0.95 * 2.0 * RADIUS);
    fc_image_free(&img);
}

/* Every pixel of `result` (one sphere of RADIUS at the origin) against the
 * analytic chord above `view_plane`; the plane must cut off a good part. */
static void check_clipped_chords(const fc_render_target *result, const fc_camera *cam, const double view_plane[4])
{
    fc_image img = {0};
    fc_error err = {0};
    CHECK_CODE(read_target(result, 1, &img, &err), FC_OK);
    const double centre[3] = {0.0, 0.0, 0.0};
    int wrong = 0, clipped = 0;
    for (uint32_t row = 0; row < SIZE; row++)
        for (uint32_t x = 0; x < SIZE; x++) {
            double full = analytic_clipped_chord(cam, centre, RADIUS, (const double[4]){0, 0, 0, 1}, x, row);
            double expected = analytic_clipped_chord(cam, centre, RADIUS, view_plane, x, row);
            clipped += expected < full - 0.05;
            wrong += fabs(pixel_f32(&img, x, row) - expected) > 2e-3;
        }
    CHECK_MSG(clipped > 100, "only %d pixels lose thickness to the floor", clipped);
    CHECK_MSG(wrong == 0, "%d pixels off the analytic clipped chord", wrong);
    fc_image_free(&img);
}

/* The thickness of `result` (one sphere of RADIUS at the origin) summed
 * over the image against the full analytic chords times the share of the
 * sphere's volume above `view_plane` (a cap of height r + h for a centre
 * at height h): the compute splat of the thickness alone takes the floor
 * per particle (surface_splat.comp.glsl). */
static void check_floor_share(const fc_render_target *result, const fc_camera *cam, const double view_plane[4])
{
    fc_image img = {0};
    fc_error err = {0};
    CHECK_CODE(read_target(result, 1, &img, &err), FC_OK);
    const double centre[3] = {0.0, 0.0, -DISTANCE};   /* in view space */
    double normal = sqrt(view_plane[0] * view_plane[0] + view_plane[1] * view_plane[1] + view_plane[2] * view_plane[2]);
    double height = (view_plane[0] * centre[0] + view_plane[1] * centre[1] + view_plane[2] * centre[2] +
                     view_plane[3]) / normal;
    double t = height / RADIUS, share = (1.0 + t) * (1.0 + t) * (2.0 - t) / 4.0;
    double full = 0.0;
    for (uint32_t row = 0; row < SIZE; row++)
        for (uint32_t x = 0; x < SIZE; x++)
            full += analytic_clipped_chord(cam, (const double[3]){0, 0, 0}, RADIUS, (const double[4]){0, 0, 0, 1}, x,
                                           row);
    CHECK_MSG(share > 0.6 && share < 0.9, "the floor leaves %g of the sphere", share);
    CHECK_MSG(fabs(image_sum(&img) / (share * full) - 1.0) < 1e-3, "thickness %g, the floor's share of %g: %g",
              image_sum(&img), full, share * full);
    fc_image_free(&img);
}

/* The passes themselves, with a floor through the lower part of the sphere
 * (the built-in floor always lies below the particles): the thickness pass,
 * and the surface splat of the depth pass with `splat`. */
static void test_floor_cuts_chords(fc_splat_method splat)
{
    fc_particle_buffer particles;
    fc_thickness_pass pass;
    fc_depth_pass depth;
    fc_error err = {0};
    CHECK_CODE(fc_particle_buffer_create(&particles, &err), FC_OK);
    CHECK_CODE(fc_thickness_pass_create(NULL, &pass, &err), FC_OK);
    CHECK_CODE(fc_depth_pass_create(NULL, &depth, &err), FC_OK);
    const float origin[3] = {0.0f, 0.0f, 0.0f};
    fc_frame frame = {.count = 1, .positions = (float *)origin};
    CHECK_CODE(fc_particle_buffer_upload(&particles, &frame, &err), FC_OK);
    fc_camera cam = axis_camera(DISTANCE, SIZE, SIZE);
    fc_view view;
    fc_view_from_camera(&cam, particles.lo, particles.hi, (float)RADIUS, &view);
    /* Tilted towards the camera, 0.2 below the centre: y + 0.3 z + 0.2 > 0 in world terms. */
    const double world_normal[3] = {0.0, 1.0, 0.3}, offset = 0.2;
    const float plane[4] = {0.0f, 1.0f, 0.3f, (float)(offset + 0.3 * DISTANCE)};
    const double view_plane[4] = {world_normal[0], world_normal[1], world_normal[2], offset + 0.3 * DISTANCE};
    depth.method = splat;
    CHECK_CODE(fc_depth_pass_run(&depth, &particles, &view, (float)RADIUS, plane, &err), FC_OK);
    CHECK(splat == FC_SPLAT_AUTO || depth.last_used == splat);
    check_clipped_chords(&depth.thickness, &cam, view_plane);
    /* The thickness alone, as the thickness pass has it splatted at reduced scales. */
    CHECK_CODE(fc_depth_pass_run_thickness(&depth, &particles, &view, (float)RADIUS, plane, &err), FC_OK);
    if (depth.last_used == FC_SPLAT_COMPUTE)
        check_floor_share(&depth.thickness, &cam, view_plane);
    else
        check_clipped_chords(&depth.thickness, &cam, view_plane);
    /* At full resolution and without a blur the thickness pass hands on the depth pass's splat. */
    fc_thickness_params params = {.radius = (float)RADIUS, .scale = 1.0f, .floor_plane = plane, .depth = &depth};
    const fc_render_target *result = NULL;
    CHECK_CODE(fc_thickness_pass_run(&pass, &particles, &view, &params, &result, &err), FC_OK);
    CHECK(result == &depth.thickness);
    fc_depth_pass_destroy(&depth);
    fc_thickness_pass_destroy(&pass);
    fc_particle_buffer_destroy(&particles);
}

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    test_stacks_at_each_scale(&f);
    test_blur_conserves_thickness(&f);
    test_filter_downsamples_and_blurs();
    test_half_resolution_sums_chords(&f);
    CHECK(fixture_splat_as_forced(&f));
    test_floor_cuts_chords(f.splat);
    fixture_close(&f);
    return test_result();
}
