/* test_reader_recentre.c — float64 positions far from the origin: a 10 x 10 x 10
 * lattice of spacing 1e-3 around x, y, z ~ 1e7, as a float64 .npy (numpy's format,
 * built byte by byte) and as a VTU with a Float64 Points array. Read with a
 * recentring, its float32 positions have the same geometry as the same data at
 * the origin to within 1e-6 of the spacing (without one, float32's step at 1e7 is
 * 1.0, and the lattice collapses); the offset is the bounds' centre, decided by
 * the first file and kept for the next; float32 files and data near the origin
 * are left alone; --select x/y/z compares in the file's coordinates. */
#include "reader_test_support.h"

#define SIDE 10
#define COUNT (SIDE * SIDE * SIDE)
#define SPACING 1e-3
#define FAR 1e7

/* Particle i's coordinate k around (1e7 + 1000, 1e7 + 2000, 1e7 + 3000), or that data moved to the origin
 * (subtracted exactly in double). */
static double coordinate(int i, int k, double origin)
{
    int digit = k == 0 ? i % SIDE : k == 1 ? i / SIDE % SIDE : i / (SIDE * SIDE);
    double far = FAR + (k + 1) * 1000.0 + (digit - 4.5) * SPACING;
    return origin == FAR ? far : far - (FAR + (k + 1) * 1000.0);
}

static bytes npy_f64(double origin)
{
    bytes b = { NULL, 0, 0 };
    char dict[128];
    int n = snprintf(dict, sizeof dict, "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, 3), }", COUNT);
    size_t padded = (10 + (size_t)n + 1 + 63) / 64 * 64 - 10;
    bytes_append(&b, "\x93NUMPY\x01\x00", 8);
    bytes_uint(&b, padded, 2, false);
    bytes_append(&b, dict, (size_t)n);
    for (size_t i = (size_t)n + 1; i < padded; i++)
        bytes_append(&b, " ", 1);
    bytes_append(&b, "\n", 1);
    for (int i = 0; i < COUNT; i++)
        for (int k = 0; k < 3; k++)
            bytes_f64(&b, coordinate(i, k, origin), false);
    return b;
}

static bytes vtu_f64(double origin)
{
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                     "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"%d\" "
                     "NumberOfCells=\"0\">\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
                     "format=\"ascii\">\n", COUNT);
    for (int i = 0; i < COUNT; i++)
        bytes_printf(&b, "%.17g %.17g %.17g\n", coordinate(i, 0, origin), coordinate(i, 1, origin),
                     coordinate(i, 2, origin));
    bytes_printf(&b, "</DataArray>\n</Points>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    return b;
}

static fc_code read_with(const bytes *b, fc_file_format format, fc_recentring *r, fc_frame *f)
{
    fc_read_options o = { .recentring = r };
    fc_error err = { FC_OK, "" };
    fc_code code = fc_read_particles_mem_with(b->data, b->len, format, "far", &o, f, &err);
    CHECK_MSG(code == FC_OK, "%s", err.message);
    return code;
}

/* The largest difference, over particles and axes, of the positions relative to particle 0. */
static double geometry_error(const fc_frame *a, const fc_frame *b)
{
    double worst = 0.0;
    for (uint64_t i = 0; i < a->count && i < b->count; i++)
        for (int k = 0; k < 3; k++) {
            double da = (double)a->positions[3 * i + k] - a->positions[k];
            double db = (double)b->positions[3 * i + k] - b->positions[k];
            worst = fabs(da - db) > worst ? fabs(da - db) : worst;
        }
    return worst;
}

static void test_format(fc_file_format format, bytes (*make)(double), const char *what)
{
    bytes far = make(FAR), near = make(0.0);
    fc_recentring at_origin = { 0 }, recentred = { 0 };
    fc_frame f_near, f_far, f_plain;
    if (read_with(&near, format, &at_origin, &f_near) != FC_OK || read_with(&far, format, &recentred, &f_far) != FC_OK)
        return;
    CHECK_MSG(at_origin.decided && !at_origin.applied, "%s: data near the origin was recentred", what);
    CHECK_MSG(recentred.applied && fabs(recentred.offset[0] - (FAR + 1000)) < 1e-6 &&
                  fabs(recentred.offset[2] - (FAR + 3000)) < 1e-6,
              "%s: offset %.17g %.17g %.17g", what, recentred.offset[0], recentred.offset[1], recentred.offset[2]);
    double error = geometry_error(&f_far, &f_near);
    CHECK_MSG(f_far.count == COUNT && error <= 1e-6 * SPACING, "%s: geometry differs by %g (spacing %g)", what, error,
              SPACING);
    /* Recentred about the bounds' centre: the lattice spans +-4.5 spacings around 0. */
    CHECK_MSG(fabs(f_far.positions[0] + 4.5 * SPACING) < 1e-6 * SPACING, "%s: first x %.9g", what, f_far.positions[0]);
    /* Without a recentring the float32 conversion keeps no spacing at all. */
    fc_error err = { FC_OK, "" };
    CHECK(fc_read_particles_mem(far.data, far.len, format, "plain", &f_plain, &err) == FC_OK);
    CHECK_MSG(geometry_error(&f_plain, &f_near) > 0.5 * SPACING, "%s: float32 at 1e7 kept the spacing?", what);
    /* The same state keeps the first file's offset for the next (a sequence stays put), even near the origin. */
    fc_frame f_next;
    if (read_with(&near, format, &recentred, &f_next) == FC_OK)
        CHECK_MSG(fabs((double)f_next.positions[0] - (coordinate(0, 0, 0.0) - recentred.offset[0])) < 1.0,
                  "%s: next file at %g", what, f_next.positions[0]);
    fc_frame_free(&f_next);
    fc_frame_free(&f_near);
    fc_frame_free(&f_far);
    fc_frame_free(&f_plain);
    bytes_free(&far);
    bytes_free(&near);
}

/* --select x/y/z speak the file's coordinates; float32 files are never shifted. */
static void test_select_and_float32(void)
{
    bytes far = npy_f64(FAR);
    fc_recentring r = { 0 };
    fc_read_options o = { .recentring = &r, .select_count = 1 };
    fc_error err = { FC_OK, "" };
    CHECK(fc_select_parse("x<10001000", &o.select[0], &err) == FC_OK); /* digits 0..4 of x */
    fc_frame f;
    CHECK_MSG(fc_read_particles_mem_with(far.data, far.len, FC_FILE_NPY, "far", &o, &f, &err) == FC_OK, "%s",
              err.message);
    CHECK_MSG(f.count == COUNT / 2, "x<10001000 kept %llu", (unsigned long long)f.count);
    fc_frame_free(&f);
    bytes_free(&far);

    bytes f32 = { NULL, 0, 0 };
    for (int k = 0; k < 3; k++)
        bytes_f32(&f32, 1e7f, false);
    fc_recentring untouched = { 0 };
    fc_read_options plain = { .recentring = &untouched };
    CHECK(fc_read_particles_mem_with(f32.data, f32.len, FC_FILE_F32, "f.f32", &plain, &f, &err) == FC_OK);
    CHECK(f.count == 1 && f.positions[0] == 1e7f && !untouched.decided);
    fc_frame_free(&f);
    bytes_free(&f32);
}

int main(void)
{
    test_format(FC_FILE_NPY, npy_f64, "npy");
    test_format(FC_FILE_VTK_XML, vtu_f64, "vtu");
    test_select_and_float32();
    return test_result();
}
