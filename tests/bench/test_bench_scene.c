/* test_bench_scene.c — the benchmark's drop scene and its .f32 export: the peer
 * comparison is only fair if VTK reads exactly the particles fluidcast renders,
 * with the radius fluidcast would pick itself.
 * argv[1]: a writable directory for the exported files. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench_output.h"
#include "fc_frame.h"
#include "particle_reader.h"
#include "scene.h"
#include "test_util.h"

/* Pool 2 x 2 x 0.12 plus a drop of radius 0.3 (scene.h). */
static const double scene_volume = 2.0 * 2.0 * 0.12 + 4.0 / 3.0 * M_PI * 0.3 * 0.3 * 0.3;

static void test_exact_count_inside_scene(uint64_t count)
{
    fc_frame frame;
    float h = 0.0f;
    CHECK_CODE(bench_scene_drop(count, &frame, &h, NULL), FC_OK);
    CHECK_MSG(frame.count == count, "count %llu, asked %llu", (unsigned long long)frame.count,
              (unsigned long long)count);
    /* every point is a lattice point of the pool or the drop, moved by at most 0.1 h per axis */
    const float slack = 0.1f * h + 1e-6f;
    uint64_t outside = 0;
    for (uint64_t i = 0; i < frame.count; i++) {
        const float *p = frame.positions + 3 * i;
        const float dz = p[2] - 0.6f;
        const int in_pool = fabsf(p[0]) <= 1.0f + slack && fabsf(p[1]) <= 1.0f + slack &&
                            p[2] >= -slack && p[2] <= 0.12f + slack;
        const int in_drop = sqrtf(p[0] * p[0] + p[1] * p[1] + dz * dz) <= 0.3f + 2.0f * slack;
        outside += !in_pool && !in_drop;
    }
    CHECK_MSG(outside == 0, "%llu of %llu points outside the scene", (unsigned long long)outside,
              (unsigned long long)count);
    fc_frame_free(&frame);
}

/* The spacing is the one that fills the scene's volume with `count` points,
 * shrunk by the few percent the lattice needs to hold them all. */
static void test_spacing_fills_volume(void)
{
    const uint64_t count = 20000;
    fc_frame frame;
    float h = 0.0f;
    CHECK_CODE(bench_scene_drop(count, &frame, &h, NULL), FC_OK);
    const double ideal = cbrt(scene_volume / (double)count);
    CHECK_MSG(h <= 1.0001 * ideal && h >= 0.9 * ideal, "spacing %g, volume / count gives %g", h, ideal);
    fc_frame_free(&frame);
}

/* The benchmark's radius is close to the one fluidcast estimates for radius =
 * auto: 0.9 x the nearest-neighbour distance, which the jitter (up to 0.1 h per
 * axis, each way) shortens by at most 0.2 h from the lattice spacing h. */
static void test_radius_matches_estimate(void)
{
    fc_frame frame;
    float h = 0.0f;
    CHECK_CODE(bench_scene_drop(20000, &frame, &h, NULL), FC_OK);
    const float estimated = fc_frame_estimate_radius(&frame);
    const float radius = BENCH_SCENE_RADIUS_PER_SPACING * h;
    CHECK_MSG(estimated <= radius && estimated >= 0.8f * radius, "estimated %g, benchmark radius %g",
              estimated, radius);
    fc_frame_free(&frame);
}

static void test_deterministic(void)
{
    fc_frame a, b;
    float ha, hb;
    CHECK_CODE(bench_scene_drop(3000, &a, &ha, NULL), FC_OK);
    CHECK_CODE(bench_scene_drop(3000, &b, &hb, NULL), FC_OK);
    CHECK(ha == hb);
    CHECK(memcmp(a.positions, b.positions, 3 * 3000 * sizeof(float)) == 0);
    fc_frame_free(&a);
    fc_frame_free(&b);
}

static void test_zero_particles_rejected(void)
{
    fc_frame frame;
    float h;
    fc_error err;
    CHECK_CODE(bench_scene_drop(0, &frame, &h, &err), FC_ERR_USAGE);
    CHECK(frame.positions == NULL);
}

/* Exact little-endian bytes, whatever the host. */
static void test_f32_bytes(const char *dir)
{
    float xyz[6] = {1.0f, -2.0f, 0.5f, 0.0f, 3.0f, -0.25f};
    const fc_frame frame = {.count = 2, .positions = xyz};
    const unsigned char expected[24] = {
        0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0xc0, 0x00, 0x00, 0x00, 0x3f,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40, 0x40, 0x00, 0x00, 0x80, 0xbe,
    };
    char path[1024];
    snprintf(path, sizeof path, "%s/bench_scene_bytes.f32", dir);
    CHECK_CODE(bench_write_scene_f32(&frame, path, NULL), FC_OK);
    unsigned char got[32];
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (!f)
        return;
    const size_t n = fread(got, 1, sizeof got, f);
    fclose(f);
    CHECK_MSG(n == sizeof expected, "%zu bytes written", n);
    CHECK(memcmp(got, expected, sizeof expected) == 0);
    remove(path);
}

/* What the peer benchmark reads is what the benchmark renders, bit for bit;
 * 5000 particles span several of the writer's chunks. */
static void test_f32_round_trip(const char *dir)
{
    fc_frame scene, read;
    float h;
    CHECK_CODE(bench_scene_drop(5000, &scene, &h, NULL), FC_OK);
    char path[1024];
    snprintf(path, sizeof path, "%s/bench_scene_5000.f32", dir);
    CHECK_CODE(bench_write_scene_f32(&scene, path, NULL), FC_OK);
    fc_error err;
    CHECK_CODE(fc_read_particles(path, &read, &err), FC_OK);
    CHECK(read.count == scene.count);
    if (read.count == scene.count)
        CHECK(memcmp(read.positions, scene.positions, 3 * scene.count * sizeof(float)) == 0);
    fc_frame_free(&scene);
    fc_frame_free(&read);
    remove(path);
}

static void test_unwritable_path(void)
{
    float xyz[3] = {0};
    const fc_frame frame = {.count = 1, .positions = xyz};
    fc_error err;
    CHECK_CODE(bench_write_scene_f32(&frame, "/nonexistent-fluidcast-dir/scene.f32", &err), FC_ERR_IO);
    CHECK(strstr(err.message, "/nonexistent-fluidcast-dir/scene.f32") != NULL);
    CHECK_CODE(bench_write_bytes("x", 1, "/nonexistent-fluidcast-dir/image.png", &err), FC_ERR_IO);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    test_exact_count_inside_scene(1);
    test_exact_count_inside_scene(1000);
    test_exact_count_inside_scene(16384);
    test_spacing_fills_volume();
    test_radius_matches_estimate();
    test_deterministic();
    test_zero_particles_rejected();
    test_f32_bytes(dir);
    test_f32_round_trip(dir);
    test_unwritable_path();
    return test_result();
}
