/* test_reader_hdf5.c — HDF5 files written by h5py (make_hdf5_fixtures.py) in the
 * layouts of SWIFT/GADGET, PySPH and H5Part, float32 and float64, with and without
 * the optional arrays: the reader returns exactly the values written. Then the
 * options (--dataset, --step), and the files it must refuse with a clear reason:
 * wrong rank or shape, counts that disagree, a huge claimed shape, unwritten data,
 * strings, NaN, every truncation and a corrupted superblock. Skipped (77) when
 * the fixtures could not be written (no h5py). */
#include <hdf5.h>
#include <sys/stat.h>
#include "reader_test_support.h"

#define N 100

static const char *fixtures;

static const char *fixture(const char *name)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s", fixtures, name);
    return path;
}

static void check_particle(const fc_frame *f, uint64_t at, uint64_t i, double x_shift, const char *what)
{
    check_position(f, at, (float)((3.0 * i + 0) * 0.25 - 1.5 + x_shift), (float)((3.0 * i + 1) * 0.25 - 1.5),
                   (float)((3.0 * i + 2) * 0.25 - 1.5));
    if (f->velocity)
        check_velocity(f, at, (float)(0.5 * i), (float)(0.5 * i + 1), (float)(0.5 * i + 2));
    if (f->density)
        CHECK_MSG(f->density[at] == (float)(1000.0 + i), "%s: density[%llu] = %g", what, (unsigned long long)at,
                  f->density[at]);
    if (f->ids)
        CHECK_MSG(f->ids[at] == 7 * i + 3, "%s: ids[%llu] = %u", what, (unsigned long long)at, f->ids[at]);
    /* The render radius is 0.9 h / 1.2348 (reader_hdf5.c: SWIFT's eta). */
    double radius = 0.01 * (double)(i + 1) * 0.9 / 1.2348;
    if (f->radius)
        CHECK_MSG(fabs(f->radius[at] - radius) <= 1e-6 * radius, "%s: radius[%llu] = %g, expected %g", what,
                  (unsigned long long)at, f->radius[at], radius);
}

static void read_ok(const char *name, const fc_read_options *o, fc_frame *f)
{
    fc_error err = { FC_OK, "" };
    fc_code code = fc_read_particles_with(fixture(name), o, f, &err);
    CHECK_MSG(code == FC_OK, "%s: %s", name, err.message);
}

static void test_swift(void)
{
    static const char *const full[] = { "swift_f32.h5", "swift_f64.hdf5", "snapshot_0000" };
    for (size_t k = 0; k < sizeof full / sizeof full[0]; k++) {
        fc_frame f;
        read_ok(full[k], NULL, &f);
        CHECK_MSG(f.count == N && f.velocity && f.density && f.ids && f.radius, "%s: %llu particles", full[k],
                  (unsigned long long)f.count);
        for (uint64_t i = 0; i < f.count; i++)
            check_particle(&f, i, i, 0, full[k]);
        fc_frame_free(&f);
    }
    static const char *const minimal[] = { "swift_minimal.h5", "userblock.h5" };
    for (size_t k = 0; k < 2; k++) {
        fc_frame f;
        read_ok(minimal[k], NULL, &f);
        CHECK_MSG(f.count == N && !f.velocity && !f.density && !f.ids && !f.radius, "%s", minimal[k]);
        for (uint64_t i = 0; i < f.count; i++)
            check_particle(&f, i, i, 0, minimal[k]);
        fc_frame_free(&f);
    }
}

static void test_pysph(void)
{
    fc_frame f;
    read_ok("pysph_f32.hdf5", NULL, &f);
    CHECK_MSG(f.count == N && f.velocity && f.density && !f.ids, "pysph_f32: %llu", (unsigned long long)f.count);
    for (uint64_t i = 0; i < f.count; i++)
        check_particle(&f, i, i, 0, "pysph_f32");
    fc_frame_free(&f);
    /* fluid (100, with u v w) then solid (10, without): velocity is dropped, density kept for all. */
    read_ok("pysph_f64.hdf5", NULL, &f);
    CHECK_MSG(f.count == N + 10 && !f.velocity && f.density && !f.ids, "pysph_f64: %llu", (unsigned long long)f.count);
    for (uint64_t i = 0; i < N && i < f.count; i++)
        check_particle(&f, i, i, 0, "pysph_f64 fluid");
    for (uint64_t i = 0; i < 10 && N + i < f.count; i++)
        check_particle(&f, N + i, i, 100, "pysph_f64 solid");
    fc_frame_free(&f);
}

/* --select over what the file names beyond the frame: PySPH's m (0.25 fluid, 0.75 solid), SWIFT's Masses. */
static void test_select(void)
{
    fc_frame f;
    fc_read_options o = { 0 };
    fc_error err = { FC_OK, "" };
    CHECK(fc_select_parse("m>0.5", &o.select[o.select_count++], &err) == FC_OK);
    read_ok("pysph_f64.hdf5", &o, &f);
    CHECK_MSG(f.count == 10, "m>0.5: %llu", (unsigned long long)f.count);
    for (uint64_t i = 0; i < f.count; i++)
        check_particle(&f, i, i, 100, "solid by m");
    fc_frame_free(&f);
    o.select_count = 0;
    CHECK(fc_select_parse("Masses=0.5", &o.select[o.select_count++], &err) == FC_OK);
    CHECK(fc_select_parse("ParticleIDs<0", &o.select[o.select_count++], &err) == FC_OK);
    CHECK_CODE(fc_read_particles_with(fixture("swift_f32.h5"), &o, &f, &err), FC_ERR_USAGE);
    CHECK_MSG(strstr(err.message, "no attribute 'ParticleIDs' (this file has: x, y, z, density, vx, vy, vz, speed, "
                                  "id, radius, Masses)") != NULL, "%s", err.message);
    o.select[1] = o.select[0];
    CHECK(fc_select_parse("id>=left", &o.select[1], &err) == FC_ERR_USAGE);
    CHECK(fc_select_parse("id>=689", &o.select[1], &err) == FC_OK); /* ids 7 i + 3: i >= 98 */
    read_ok("swift_f32.h5", &o, &f);
    CHECK_MSG(f.count == 2 && f.ids && f.ids[0] == 689 && f.ids[1] == 696, "%llu", (unsigned long long)f.count);
    fc_frame_free(&f);
}

static void test_h5part(void)
{
    fc_frame f;
    read_ok("steps.h5part", NULL, &f);
    CHECK(f.count == N && f.velocity && f.ids && !f.density);
    for (uint64_t i = 0; i < f.count; i++)
        check_particle(&f, i, i, 0, "Step#0");
    fc_frame_free(&f);
    fc_read_options step1 = { .has_step = true, .step = 1 };
    read_ok("steps.h5part", &step1, &f);
    CHECK(f.count == N);
    for (uint64_t i = 0; i < f.count; i++)
        check_particle(&f, i, i, 1, "Step#1");
    fc_frame_free(&f);
    fc_error err = { FC_OK, "" };
    fc_read_options step9 = { .has_step = true, .step = 9 };
    CHECK_CODE(fc_read_particles_with(fixture("steps.h5part"), &step9, &f, &err), FC_ERR_PARSE);
    CHECK_MSG(strstr(err.message, "no group Step#9 (the first step is Step#0)") != NULL, "%s", err.message);
}

static void test_dataset_option(void)
{
    static const char *const specs[] = { "/sim/pos", "sim/pos", "x=/cols/a,y=/cols/b,z=cols/c" };
    for (size_t k = 0; k < 3; k++) {
        fc_frame f;
        fc_read_options o = { .dataset = specs[k] };
        read_ok("custom.h5", &o, &f);
        CHECK_MSG(f.count == N, "%s", specs[k]);
        for (uint64_t i = 0; i < f.count; i++)
            check_particle(&f, i, i, 0, specs[k]);
        fc_frame_free(&f);
    }
    fc_frame f;
    fc_read_options group = { .dataset = "/PartType0" };
    read_ok("swift_f64.hdf5", &group, &f);
    CHECK(f.count == N && f.density && f.velocity);
    fc_frame_free(&f);
    static const struct { const char *spec, *needle; } bad[] = {
        { "/nothing", "--dataset '/nothing': no such group or dataset" },
        { "x=/cols/a,y=/cols/b", "expected x=PATH,y=PATH,z=PATH" },
        { "x=/cols/a,x=/cols/b,z=/cols/c", "expected x=PATH,y=PATH,z=PATH" },
        { "/cols/a", "dataset '/cols/a' has shape (100): expected (N, 3)" },
        { "/cols", "group '/cols' has no positions" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        fc_error err = { FC_OK, "" };
        fc_read_options o = { .dataset = bad[k].spec };
        CHECK(fc_read_particles_with(fixture("custom.h5"), &o, &f, &err) != FC_OK);
        CHECK_MSG(strstr(err.message, bad[k].needle) != NULL, "%s: %s", bad[k].spec, err.message);
        CHECK(frame_is_empty(&f));
    }
}

static void test_refusals(void)
{
    static const struct { const char *name, *needle; } cases[] = {
        { "wrong_rank.h5", "dataset '/PartType0/Coordinates' has shape (100): expected (N, 3)" },
        { "wrong_shape.h5", "dataset '/PartType0/Coordinates' has shape (100, 4): expected (N, 3)" },
        { "mismatch.h5", "dataset '/PartType0/Density' holds 99 particles, the positions 100" },
        { "mismatch_xyz.h5", "dataset '/y' holds 99 particles, the positions 100" },
        { "huge.h5", "claims 1099511627776 x 3 values: more than a file of" },
        { "unwritten.h5", "has no values written" },
        { "strings.h5", "dataset '/PartType0/Coordinates' is not numeric" },
        { "nan.h5", "particle 7: y = nan is not a finite value" },
        { "no_particles.h5", "no particles found: expected PartType0 (SWIFT/GADGET)" },
        { "ids_too_big.h5", "particle 0: id = 1.09951e+12 is not an integer" },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        fc_frame f;
        fc_error err = { FC_OK, "" };
        CHECK_CODE(fc_read_particles(fixture(cases[k].name), &f, &err), FC_ERR_PARSE);
        CHECK_MSG(strstr(err.message, fixture(cases[k].name)) == err.message, "%s", err.message);
        CHECK_MSG(strstr(err.message, cases[k].needle) != NULL, "%s: %s", cases[k].name, err.message);
        CHECK(frame_is_empty(&f));
    }
}

static bytes load(const char *name)
{
    bytes b = { NULL, 0, 0 };
    FILE *file = fopen(fixture(name), "rb");
    CHECK(file != NULL);
    uint8_t chunk[4096];
    size_t n;
    while (file && (n = fread(chunk, 1, sizeof chunk, file)) > 0)
        bytes_append(&b, chunk, n);
    if (file)
        fclose(file);
    return b;
}

/* Cut anywhere, or with its superblock overwritten, a file is refused with the file named (libhdf5's reason
 * after it), never a crash; an HDF5 signature is required when the format says HDF5. */
static void test_damaged(void)
{
    bytes good = load("swift_f32.h5");
    fc_frame f;
    fc_error err = { FC_OK, "" };
    CHECK_CODE(fc_read_particles_mem(good.data, good.len, FC_FILE_UNKNOWN, "mem.h5", &f, &err), FC_OK);
    CHECK(f.count == N);
    fc_frame_free(&f);
    for (size_t cut = 0; cut < good.len; cut += cut < 64 ? 1 : 37) {
        fc_code code = fc_read_particles_mem(good.data, cut, FC_FILE_HDF5, "cut.h5", &f, &err);
        CHECK_MSG(code != FC_OK || f.count == N, "cut at %zu: %llu particles", cut, (unsigned long long)f.count);
        if (code != FC_OK)
            CHECK_MSG(code == FC_ERR_PARSE && strncmp(err.message, "cut.h5: ", 8) == 0 && frame_is_empty(&f),
                      "cut at %zu: %d %s", cut, (int)code, err.message);
        fc_frame_free(&f);
    }
    bytes bad = { NULL, 0, 0 };
    bytes_append(&bad, good.data, good.len);
    memset(bad.data + 8, 0xff, 40); /* version numbers, sizes and addresses of the superblock */
    CHECK_CODE(fc_read_particles_mem(bad.data, bad.len, FC_FILE_HDF5, "super.h5", &f, &err), FC_ERR_PARSE);
    CHECK_MSG(strstr(err.message, "super.h5: not a readable HDF5 file") == err.message, "%s", err.message);
    memset(bad.data, 0, 8);
    CHECK_CODE(fc_read_particles_mem(bad.data, bad.len, FC_FILE_HDF5, "nosig.h5", &f, &err), FC_ERR_PARSE);
    CHECK_MSG(strstr(err.message, "nosig.h5: not an HDF5 file") == err.message, "%s", err.message);
    bytes_free(&bad);
    bytes_free(&good);
}

int main(void)
{
    fixtures = getenv("FC_HDF5_FIXTURES");
    struct stat info;
    if (fixtures == NULL || stat(fixture("swift_f32.h5"), &info) != 0) {
        printf("SKIP: no h5py-written fixtures (FC_HDF5_FIXTURES; apt-get install python3-h5py)\n");
        return 77;
    }
    test_swift();
    test_pysph();
    test_select();
    test_h5part();
    test_dataset_option();
    test_refusals();
    test_damaged();
    /* The reader closes every libhdf5 object it opens, on every path (LeakSanitizer cannot tell ours
     * from libhdf5's own leaks on damaged files: tests/sanitizer/lsan.supp). */
    ssize_t open_objects = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
    CHECK_MSG(open_objects == 0, "%zd libhdf5 objects left open", open_objects);
    return test_result();
}
