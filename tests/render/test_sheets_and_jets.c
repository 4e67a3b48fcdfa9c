/* test_sheets_and_jets.c — thin fluid stays a surface (issue 26, items 6 and
 * 8), through the whole pipeline with its default settings and either
 * kernel: a jittered two-layer sheet facing the camera has no pinhole at
 * three sizes on screen (projected radii from about 2.5 to 19 pixels), and a
 * jet of particles in a row, drawn from the side, is one connected surface in
 * the smoothed depth, not a string of beads. The fluid mask is the smoothed
 * depth's nonzero pixels: what the composite shades as water. Run with
 * "fragment" and "compute", once per surface splat (depth_pass.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_settings.h"
#include "render_fixture.h"
#include "test_util.h"

#define SPACING 0.02f
#define SUGGESTED_RADII 0.55f   /* the splash data's suggested radius, in spacings */
#define SIZE 256u

static uint32_t lcg(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

static float jitter(uint32_t *state, float amplitude)
{
    return ((float)lcg(state) / 16777216.0f - 0.5f) * 2.0f * amplitude;
}

static const fc_kernel KERNELS[2] = {FC_KERNEL_SPHERE, FC_KERNEL_ANISOTROPIC};
static const char *const KERNEL_NAMES[2] = {"sphere", "anisotropic"};

static fc_image render_mask(render_fixture *f, const float *x, int count, const fc_camera *cam, fc_kernel kernel)
{
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = SUGGESTED_RADII * SPACING;
    settings.kernel = kernel;
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, x, (uint64_t)count, cam, &settings, FC_AOV_SMOOTHED_DEPTH, 0, &depth), FC_OK);
    CHECK(fixture_splat_as_forced(f));
    return depth;
}

/* Two jittered layers of 24 x 24 particles facing the camera, the second
 * offset by half a spacing in x and y and 0.7 spacings behind (the issue's
 * sheet, as test_ellipsoid_splat.c builds it). */
static int two_layer_sheet(float *x)
{
    uint32_t state = 4242u;
    int n = 0;
    for (int layer = 0; layer < 2; layer++)
        for (int j = 0; j < 24; j++)
            for (int i = 0; i < 24; i++, n++) {
                float shift = 0.5f * (float)layer;
                x[3 * n] = ((float)i - 11.5f + shift) * SPACING + jitter(&state, 0.15f * SPACING);
                x[3 * n + 1] = ((float)j - 11.5f + shift) * SPACING + jitter(&state, 0.15f * SPACING);
                x[3 * n + 2] = -0.7f * SPACING * (float)layer + jitter(&state, 0.15f * SPACING);
            }
    return n;
}

/* Pixels without fluid inside the square [lo, hi]² of the image. */
static int empty_pixels_in(const fc_image *depth, double lo, double hi)
{
    int empty = 0;
    for (uint32_t row = 0; row < depth->height; row++)
        for (uint32_t x = 0; x < depth->width; x++)
            if (x + 0.5 >= lo && x + 0.5 <= hi && row + 0.5 >= lo && row + 0.5 <= hi &&
                pixel_f32(depth, x, row) == 0.0f)
                empty++;
    return empty;
}

static void test_sheet_has_no_pinholes(render_fixture *f)
{
    float x[3 * 1152];
    int count = two_layer_sheet(x);
    /* Camera distances giving the particles about 19, 4.8 and 2.4 pixels of projected radius. */
    const double distances[3] = {0.2, 0.8, 1.6};
    for (int d = 0; d < 3; d++) {
        fc_camera cam = axis_camera(distances[d], SIZE, SIZE);
        /* The interior: two spacings in from the sheet's edges, clipped to the image. */
        const double corner[3] = {-(11.5 - 2.0) * SPACING, (11.5 - 2.0) * SPACING, 0.0};
        double lo, unused;
        analytic_project(&cam, corner, &lo, &unused);
        lo = fmax(lo, 0.0);
        double hi = SIZE - lo;
        for (int k = 0; k < 2; k++) {
            fc_image depth = render_mask(f, x, count, &cam, KERNELS[k]);
            int pinholes = empty_pixels_in(&depth, lo, hi);
            printf("sheet at distance %.1f, %s kernel: %d pinholes in %.0f^2 px\n", distances[d], KERNEL_NAMES[k],
                   pinholes, hi - lo);
            CHECK_MSG(pinholes == 0, "%d pinholes in the %s sheet at distance %g", pinholes, KERNEL_NAMES[k],
                      distances[d]);
            fc_image_free(&depth);
        }
    }
}

/* The 4-connected components of the image's nonzero pixels (flood fill with an explicit stack). */
static int connected_components(const fc_image *depth)
{
    uint32_t w = depth->width, h = depth->height;
    unsigned char *seen = calloc((size_t)w * h, 1);
    uint32_t *stack = malloc((size_t)w * h * sizeof *stack);
    CHECK(seen && stack);
    int components = 0;
    for (uint32_t start = 0; start < w * h; start++) {
        if (seen[start] || pixel_f32(depth, start % w, start / w) == 0.0f)
            continue;
        components++;
        size_t top = 0;
        stack[top++] = start;
        seen[start] = 1;
        while (top > 0) {
            uint32_t p = stack[--top], px = p % w, row = p / w;
            const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
            for (int n = 0; n < 4; n++) {
                int64_t nx = (int64_t)px + dx[n], ny = (int64_t)row + dy[n];
                if (nx < 0 || ny < 0 || nx >= w || ny >= h)
                    continue;
                uint32_t q = (uint32_t)ny * w + (uint32_t)nx;
                if (!seen[q] && pixel_f32(depth, (uint32_t)nx, (uint32_t)ny) != 0.0f) {
                    seen[q] = 1;
                    stack[top++] = q;
                }
            }
        }
    }
    free(seen);
    free(stack);
    return components;
}

/* A jet: 60 particles a spacing apart along a slightly tilted line, each
 * jittered by 0.1 spacings, seen from the side. */
static void test_jet_is_one_surface(render_fixture *f)
{
    enum { JET = 60 };
    float x[3 * JET];
    uint32_t state = 777u;
    for (int i = 0; i < JET; i++) {
        float t = ((float)i - 0.5f * (JET - 1)) * SPACING;
        x[3 * i] = t * 0.96f + jitter(&state, 0.1f * SPACING);
        x[3 * i + 1] = t * 0.28f + jitter(&state, 0.1f * SPACING);
        x[3 * i + 2] = jitter(&state, 0.1f * SPACING);
    }
    fc_camera cam = axis_camera(1.6, SIZE, SIZE);
    for (int k = 0; k < 2; k++) {
        fc_image depth = render_mask(f, x, JET, &cam, KERNELS[k]);
        int components = connected_components(&depth);
        printf("jet, %s kernel: %d connected component(s)\n", KERNEL_NAMES[k], components);
        CHECK_MSG(components == 1, "the %s jet breaks into %d pieces", KERNEL_NAMES[k], components);
        fc_image_free(&depth);
    }
}

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    test_sheet_has_no_pinholes(&f);
    test_jet_is_one_surface(&f);
    fixture_close(&f);
    return test_result();
}
