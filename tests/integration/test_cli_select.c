/* test_cli_select.c — --select through the real fluidcast binary and a real
 * fluidcastd that accepts at most 2000 particles per frame: a DualSPHysics CSV
 * (';', units in the names, Type 3 = fluid, 0 = fixed boundary) of a 1000-particle
 * fluid cube over an 1800-particle boundary slab. The whole file (2800) is
 * refused by the daemon; --select Type=3 and --select Type=0 render, and the
 * fluid-only image shows background where the boundary slab projects, which the
 * boundary-only image covers. Also `render` and `stream` take it, and the errors:
 * an unknown attribute (the message lists the file's), a selection that keeps
 * nothing (named), a malformed selection (usage). */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "support/daemon_process.h"
#include "support/image_decode.h"
#include "support/tinted_look.h"
#include "test_util.h"

#define FLUID_SIDE 10   /* 10^3 fluid particles */
#define SLAB_SIDE 30    /* 30 x 30 x 2 boundary particles */

typedef struct test_env {
    char dir[64];
    char server[32];
} test_env;

static const char *path_in(const test_env *env, const char *name, char *out, size_t size)
{
    snprintf(out, size, "%s/%s", env->dir, name);
    return out;
}

static void row(FILE *f, unsigned *id, double x, double y, double z, int type)
{
    fprintf(f, "%.6e;%.6e;%.6e;%u;0;0;0;1000;%d;%d;\n", x, y, z, (*id)++, type, type == 3 ? 1 : 0);
}

/* The fluid cube around (0, 0, 0.3), spacing 0.1; the slab at z = -0.6, -0.5 spanning x, y in [-1.5, 1.5]. */
static bool write_dualsphysics_csv(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    fputs("Pos.x [m];Pos.y [m];Pos.z [m];Idp;Vel.x [m/s];Vel.y [m/s];Vel.z [m/s];Rhop [kg/m^3];Type;Mk;\n", f);
    unsigned id = 0;
    for (int i = 0; i < SLAB_SIDE; i++)
        for (int j = 0; j < SLAB_SIDE; j++)
            for (int k = 0; k < 2; k++)
                row(f, &id, -1.45 + 0.1 * i, -1.45 + 0.1 * j, -0.6 + 0.1 * k, 0);
    for (int i = 0; i < FLUID_SIDE; i++)
        for (int j = 0; j < FLUID_SIDE; j++)
            for (int k = 0; k < FLUID_SIDE; k++)
                row(f, &id, -0.45 + 0.1 * i, -0.45 + 0.1 * j, -0.15 + 0.1 * k, 3);
    return fclose(f) == 0;
}

static bool decode_png(const char *path, fc_decoded_image *out)
{
    size_t size;
    uint8_t *data = read_whole_file(path, &size);
    fc_error err;
    fc_code code = data ? fc_decode_image(data, size, ".png", 0, out, &err) : FC_ERR_IO;
    CHECK_MSG(code == FC_OK, "decoding %s", path);
    free(data);
    return code == FC_OK;
}

static int distance_at(const fc_decoded_image *a, const fc_decoded_image *b, uint32_t x, uint32_t y)
{
    const uint8_t *p = (const uint8_t *)a->pixels + ((size_t)y * a->width + x) * a->channels;
    const uint8_t *q = (const uint8_t *)b->pixels + ((size_t)y * b->width + x) * b->channels;
    return abs(p[0] - q[0]) + abs(p[1] - q[1]) + abs(p[2] - q[2]);
}

/* 160x120 from (0, -5, 0) at the origin, fov 40: 33 px per unit; the slab's rows are about 76..80,
 * its columns 30..130; the cube's rows 35..65, columns 65..95. */
static void snapshot(const test_env *env, const char *select, const char *png, cli_result *r)
{
    char csv[128];
    const char *args[] = { "snapshot", path_in(env, "case.csv", csv, sizeof csv), "-o", png, "--server", env->server,
                           "--size", "160x120", "--eye", "0,-5,0", "--target", "0,0,0", "--up", "z", "--radius",
                           "0.07", "--absorption", TINTED_LOOK_ABSORPTION, select ? "--select" : NULL, select, NULL };
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, r);
}

static void test_snapshot_select(const test_env *env)
{
    char all_png[128], fluid_png[128], bound_png[128];
    cli_result r;
    snapshot(env, NULL, path_in(env, "all.png", all_png, sizeof all_png), &r);
    CHECK_MSG(r.status == 5 && strstr(r.err, "2800") != NULL, "whole file: status %d, %s", r.status, r.err);
    snapshot(env, "Type=3", path_in(env, "fluid.png", fluid_png, sizeof fluid_png), &r);
    CHECK_MSG(r.status == 0, "Type=3: %d %s", r.status, r.err);
    snapshot(env, "Type=0", path_in(env, "bound.png", bound_png, sizeof bound_png), &r);
    CHECK_MSG(r.status == 0, "Type=0: %d %s", r.status, r.err);
    fc_decoded_image fluid = { 0 }, bound = { 0 };
    if (decode_png(fluid_png, &fluid) && decode_png(bound_png, &bound)) {
        static const uint32_t slab[][2] = { { 40, 78 }, { 120, 78 }, { 60, 79 } };
        for (size_t i = 0; i < 3; i++)
            CHECK_MSG(distance_at(&fluid, &bound, slab[i][0], slab[i][1]) > 30, "slab pixel %u,%u alike",
                      slab[i][0], slab[i][1]);
        CHECK_MSG(distance_at(&fluid, &bound, 80, 50) > 30, "the cube's pixel alike");
        CHECK_MSG(distance_at(&fluid, &bound, 80, 5) <= 6, "sky pixel differs: %d", distance_at(&fluid, &bound, 80, 5));
    }
    fc_decoded_image_free(&fluid);
    fc_decoded_image_free(&bound);
    /* Two selections: both must hold (the fluid's upper half: z > 0.3). */
    const char *args[] = { "snapshot", path_in(env, "case.csv", (char[128]){ 0 }, 128), "-o", fluid_png, "--server",
                           env->server, "--size", "160x120", "--select", "Type=0,3", "--select", "Mk!=0",
                           "--select", "z>0.3", "--radius", "0.07", NULL };
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, &r);
    CHECK_MSG(r.status == 0, "three selections: %d %s", r.status, r.err);
}

static void test_errors(const test_env *env)
{
    char png[128];
    cli_result r;
    snapshot(env, "Typ=3", path_in(env, "never.png", png, sizeof png), &r);
    CHECK_MSG(r.status == 3 && strstr(r.err, "--select 'Typ=3': no attribute 'Typ' (this file has: x, y, z, "
                                             "density, vx, vy, vz, speed, id, Type, Mk)") != NULL,
              "unknown attribute: %d %s", r.status, r.err);
    snapshot(env, "Type=7", png, &r);
    CHECK_MSG(r.status == 3 && strstr(r.err, "--select 'Type=7' keeps none of the 2800 particles") != NULL,
              "nothing kept: %d %s", r.status, r.err);
    snapshot(env, "Type~3", png, &r);
    CHECK_MSG(r.status == 2 && strstr(r.err, "--select 'Type~3': no operator") != NULL, "malformed: %d %s",
              r.status, r.err);
    snapshot(env, "Type<1,2", png, &r);
    CHECK_MSG(r.status == 2 && strstr(r.err, "one value after <, <=, > or >=") != NULL, "list after <: %d %s",
              r.status, r.err);
    CHECK(access(png, F_OK) != 0);
}

/* render (a two-file sequence) and stream read through the same options. */
static void test_render_and_stream(const test_env *env)
{
    char csv[128], copy[128], pattern[128], out_dir[128], frame1[160];
    path_in(env, "case.csv", csv, sizeof csv);
    path_in(env, "seq_0001.csv", copy, sizeof copy);
    CHECK(link(csv, copy) == 0);
    path_in(env, "seq_0002.csv", copy, sizeof copy);
    CHECK(link(csv, copy) == 0);
    path_in(env, "out_%04d.png", pattern, sizeof pattern);
    cli_result r;
    const char *seq = path_in(env, "seq_%04d.csv", (char[128]){ 0 }, 128);
    const char *refused[] = { "render", seq, "-o", pattern, "--server", env->server, "--size", "96x64", "--radius",
                              "0.07", NULL };
    cli_run(FLUIDCAST_CLI_PATH, env->dir, refused, &r);
    CHECK_MSG(r.status != 0, "render without --select: %d", r.status);
    const char *selected[] = { "render", seq, "-o", pattern, "--server", env->server, "--size", "96x64", "--radius",
                               "0.07", "--select", "Type=3", NULL };
    cli_run(FLUIDCAST_CLI_PATH, env->dir, selected, &r);
    CHECK_MSG(r.status == 0, "render --select: %d %s", r.status, r.err);
    snprintf(frame1, sizeof frame1, "%s/out_0002.png", env->dir);
    CHECK(access(frame1, F_OK) == 0);

    path_in(env, "stream", out_dir, sizeof out_dir);
    const char *stream_refused[] = { "stream", csv, "--server", env->server, "--out-dir", out_dir, "--size", "96x64",
                                     NULL };
    cli_run(FLUIDCAST_CLI_PATH, env->dir, stream_refused, &r);
    CHECK_MSG(r.status != 0, "stream without --select: %d", r.status);
    const char *stream_selected[] = { "stream", csv, "--server", env->server, "--out-dir", out_dir, "--size", "96x64",
                                      "--select", "Type!=3", NULL };
    cli_run(FLUIDCAST_CLI_PATH, env->dir, stream_selected, &r);
    CHECK_MSG(r.status == 0 && strstr(r.out, "1800") != NULL, "stream --select: %d %s %s", r.status, r.out, r.err);
}

static void remove_scratch(const test_env *env)
{
    char command[128];
    snprintf(command, sizeof command, "rm -rf '%s'", env->dir);
    if (system(command) != 0)
        fprintf(stderr, "could not remove %s\n", env->dir);
}

int main(void)
{
    test_env env;
    strcpy(env.dir, "/tmp/fluidcast-select-test-XXXXXX");
    char csv[128];
    if (!mkdtemp(env.dir) || !write_dualsphysics_csv(path_in(&env, "case.csv", csv, sizeof csv))) {
        fprintf(stderr, "cannot set up the scratch directory\n");
        return 1;
    }
    fc_test_daemon daemon;
    fc_error err;
    static const char *const daemon_args[] = { "--max-particles", "2000", NULL };
    if (fc_test_daemon_start(&daemon, daemon_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        remove_scratch(&env);
        return 1;
    }
    snprintf(env.server, sizeof env.server, "127.0.0.1:%u", (unsigned)daemon.port);
    test_snapshot_select(&env);
    test_errors(&env);
    test_render_and_stream(&env);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    remove_scratch(&env);
    return test_result();
}
