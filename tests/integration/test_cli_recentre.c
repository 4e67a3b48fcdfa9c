/* test_cli_recentre.c — float64 positions far from the origin through the real
 * fluidcast binary and a real fluidcastd: a lattice of spacing 1e-3 around
 * x, y, z ~ 1e7 as a float64 .npy and as a Float64 .vtu renders like the same
 * lattice at the origin (auto camera, same radius: the images agree pixel for
 * pixel within a small tolerance), and the CLI prints the offset once; the file
 * at the origin is not recentred. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "support/daemon_process.h"
#include "support/image_decode.h"
#include "test_util.h"

#define SIDE 12
#define COUNT (SIDE * SIDE * SIDE)

static double coordinate(int i, int k, bool far)
{
    int digit = k == 0 ? i % SIDE : k == 1 ? i / SIDE % SIDE : i / (SIDE * SIDE);
    double base = 1e7 + (k + 1) * 1000.0, value = base + (digit - 5.5) * 1e-3;
    return far ? value : value - base;
}

static bool write_npy(const char *path, bool far)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    char dict[128];
    int n = snprintf(dict, sizeof dict, "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, 3), }", COUNT);
    int padded = (10 + n + 1 + 63) / 64 * 64 - 10;
    fwrite("\x93NUMPY\x01\x00", 1, 8, f);
    uint8_t length[2] = { (uint8_t)(padded & 0xff), (uint8_t)(padded >> 8) };
    fwrite(length, 1, 2, f);
    fprintf(f, "%s%*s\n", dict, padded - n - 1, "");
    for (int i = 0; i < COUNT; i++)
        for (int k = 0; k < 3; k++) {
            double v = coordinate(i, k, far); /* little-endian machines only, like the daemon's tests */
            fwrite(&v, sizeof v, 1, f);
        }
    return fclose(f) == 0;
}

static bool write_vtu(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">"
               "<UnstructuredGrid><Piece NumberOfPoints=\"%d\" NumberOfCells=\"0\"><Points><DataArray "
               "type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n", COUNT);
    for (int i = 0; i < COUNT; i++)
        fprintf(f, "%.17g %.17g %.17g\n", coordinate(i, 0, true), coordinate(i, 1, true), coordinate(i, 2, true));
    fputs("</DataArray></Points></Piece></UnstructuredGrid></VTKFile>\n", f);
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

/* Mean absolute difference per channel, and how many pixels differ by more than 24 in sum. */
static void compare(const fc_decoded_image *a, const fc_decoded_image *b, double *mean, size_t *far_off)
{
    double sum = 0.0;
    *far_off = 0;
    size_t pixels = (size_t)a->width * a->height;
    for (size_t i = 0; i < pixels; i++) {
        const uint8_t *p = (const uint8_t *)a->pixels + i * a->channels, *q = (const uint8_t *)b->pixels + i * b->channels;
        int d = abs(p[0] - q[0]) + abs(p[1] - q[1]) + abs(p[2] - q[2]);
        sum += d / 3.0;
        *far_off += d > 24;
    }
    *mean = sum / (double)pixels;
}

static void snapshot(const char *dir, const char *server, const char *input, const char *png, cli_result *r)
{
    const char *args[] = { "snapshot", input, "-o", png, "--server", server, "--size", "128x96", "--up", "z",
                           "--radius", "0.0009", NULL };
    cli_run(FLUIDCAST_CLI_PATH, dir, args, r);
}

int main(void)
{
    char dir[] = "/tmp/fluidcast-recentre-test-XXXXXX";
    char near_npy[96], far_npy[96], far_vtu[96], near_png[96], far_png[96], vtu_png[96];
    if (!mkdtemp(dir))
        return 1;
    snprintf(near_npy, sizeof near_npy, "%s/near.npy", dir);
    snprintf(far_npy, sizeof far_npy, "%s/far.npy", dir);
    snprintf(far_vtu, sizeof far_vtu, "%s/far.vtu", dir);
    snprintf(near_png, sizeof near_png, "%s/near.png", dir);
    snprintf(far_png, sizeof far_png, "%s/far.png", dir);
    snprintf(vtu_png, sizeof vtu_png, "%s/vtu.png", dir);
    fc_test_daemon daemon;
    fc_error err;
    if (!write_npy(near_npy, false) || !write_npy(far_npy, true) || !write_vtu(far_vtu) ||
        fc_test_daemon_start(&daemon, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot set up: %s\n", err.message);
        return 1;
    }
    char server[32];
    snprintf(server, sizeof server, "127.0.0.1:%u", (unsigned)daemon.port);
    cli_result r;
    snapshot(dir, server, near_npy, near_png, &r);
    CHECK_MSG(r.status == 0 && strstr(r.out, "recentred") == NULL, "near: %d %s %s", r.status, r.out, r.err);
    snapshot(dir, server, far_npy, far_png, &r);
    CHECK_MSG(r.status == 0 && strstr(r.out, "recentred: float64 positions far from the origin, shifted by "
                                             "-(10001000, 10002000, 10003000)") != NULL,
              "far: %d %s %s", r.status, r.out, r.err);
    snapshot(dir, server, far_vtu, vtu_png, &r);
    CHECK_MSG(r.status == 0 && strstr(r.out, "recentred:") != NULL, "vtu: %d %s %s", r.status, r.out, r.err);
    fc_decoded_image near = { 0 }, far = { 0 }, vtu = { 0 };
    if (decode_png(near_png, &near) && decode_png(far_png, &far) && decode_png(vtu_png, &vtu)) {
        double mean;
        size_t off;
        compare(&near, &far, &mean, &off);
        CHECK_MSG(mean < 0.5 && off <= 10, "npy far vs near: mean %.3f, %zu pixels off", mean, off);
        compare(&near, &vtu, &mean, &off);
        CHECK_MSG(mean < 0.5 && off <= 10, "vtu far vs near: mean %.3f, %zu pixels off", mean, off);
    }
    fc_decoded_image_free(&near);
    fc_decoded_image_free(&far);
    fc_decoded_image_free(&vtu);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    const char *names[] = { near_npy, far_npy, far_vtu, near_png, far_png, vtu_png };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        unlink(names[i]);
    char captures[128];
    snprintf(captures, sizeof captures, "rm -rf '%s'", dir);
    if (system(captures) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
    return test_result();
}
