/* test_cli_hdf5.c — HDF5 files (written by h5py: tests/readers/make_hdf5_fixtures.py)
 * through the real fluidcast binary and a real fluidcastd: a SWIFT snapshot with
 * SmoothingLength renders with per-particle radii (the CLI says so and leaves the
 * radius to the file), a file without an extension is read by its signature,
 * --step and --dataset reach the reader, and a damaged layout exits 3 naming the
 * dataset. Skipped (77) without the fixtures (no h5py). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "support/daemon_process.h"
#include "test_util.h"

static const char *fixtures;

static const char *fixture(const char *name, char *out, size_t size)
{
    snprintf(out, size, "%s/%s", fixtures, name);
    return out;
}

static void snapshot(const char *dir, const char *server, const char *input, const char *const *extra, cli_result *r)
{
    char png[96];
    snprintf(png, sizeof png, "%s/out.png", dir);
    const char *args[16] = { "snapshot", input, "-o", png, "--server", server, "--size", "96x64", "--up", "z" };
    size_t n = 10;
    for (size_t i = 0; extra && extra[i] && n < 15; i++)
        args[n++] = extra[i];
    args[n] = NULL;
    unlink(png);
    cli_run(FLUIDCAST_CLI_PATH, dir, args, r);
    if (r->status == 0)
        CHECK_MSG(access(png, F_OK) == 0, "%s: no image", input);
}

int main(void)
{
    fixtures = getenv("FC_HDF5_FIXTURES");
    char path[512];
    struct stat info;
    if (fixtures == NULL || stat(fixture("swift_f64.hdf5", path, sizeof path), &info) != 0) {
        printf("SKIP: no h5py-written fixtures (FC_HDF5_FIXTURES; apt-get install python3-h5py)\n");
        return 77;
    }
    char dir[] = "/tmp/fluidcast-hdf5-test-XXXXXX";
    fc_test_daemon daemon;
    fc_error err;
    if (!mkdtemp(dir) || fc_test_daemon_start(&daemon, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot set up: %s\n", err.message);
        return 1;
    }
    char server[32];
    snprintf(server, sizeof server, "127.0.0.1:%u", (unsigned)daemon.port);
    cli_result r;
    snapshot(dir, server, fixture("swift_f64.hdf5", path, sizeof path), NULL, &r);
    CHECK_MSG(r.status == 0 && strstr(r.out, "radius: per-particle radii from the file") != NULL, "swift: %d %s %s",
              r.status, r.out, r.err);
    snapshot(dir, server, fixture("snapshot_0000", path, sizeof path), (const char *const[]){ "--radius", "0.1", NULL },
             &r);
    CHECK_MSG(r.status == 0 && strstr(r.out, "radius 0.1") != NULL, "no extension: %d %s %s", r.status, r.out, r.err);
    snapshot(dir, server, fixture("steps.h5part", path, sizeof path), (const char *const[]){ "--step", "1", NULL }, &r);
    CHECK_MSG(r.status == 0, "--step 1: %d %s", r.status, r.err);
    snapshot(dir, server, fixture("steps.h5part", path, sizeof path), (const char *const[]){ "--step", "7", NULL }, &r);
    CHECK_MSG(r.status == 3 && strstr(r.err, "no group Step#7") != NULL, "--step 7: %d %s", r.status, r.err);
    snapshot(dir, server, fixture("custom.h5", path, sizeof path),
             (const char *const[]){ "--dataset", "x=/cols/a,y=/cols/b,z=/cols/c", NULL }, &r);
    CHECK_MSG(r.status == 0, "--dataset: %d %s", r.status, r.err);
    snapshot(dir, server, fixture("pysph_f64.hdf5", path, sizeof path), (const char *const[]){ "--select", "m<0.5", NULL },
             &r);
    CHECK_MSG(r.status == 0, "PySPH --select: %d %s", r.status, r.err);
    snapshot(dir, server, fixture("mismatch.h5", path, sizeof path), NULL, &r);
    CHECK_MSG(r.status == 3 && strstr(r.err, "dataset '/PartType0/Density' holds 99 particles, the positions 100"),
              "mismatch: %d %s", r.status, r.err);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    char command[96];
    snprintf(command, sizeof command, "rm -rf '%s'", dir);
    if (system(command) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
    return test_result();
}
