/* test_reader_vtk.c — legacy VTK, ASCII and BINARY (big-endian), POLYDATA and
 * UNSTRUCTURED_GRID (legacy and 5.1 cell layouts): exact values from SCALARS
 * with lookup tables, VECTORS and FIELD arrays, SPlisHSPlasH's and DualSPHysics'
 * layouts, every skipped section kind, and
 * broken files. */
#include "reader_test_support.h"

static const float X[3][3] = { { 0.5f, -1.25f, 3.0f }, { -0.001f, 2000.0f, 0.015f }, { 10.0f, 20.0f, 30.0f } };
static const double DENSITY[3] = { 1000.5, 998.25, 1001.0 };
static const float V[3][3] = { { 0.125f, -0.25f, 4.0f }, { 0.0f, 0.0f, -9.81f }, { 1.0f, 2.0f, 3.0f } };
static const uint32_t IDS[3] = { 7, 4294967295u, 0 };

typedef enum { T_U8, T_I32, T_U32, T_I64, T_F32, T_F64 } vtype;

/* Writes n values as the VTK writer does: big-endian bytes then a newline, or text lines. */
static void put(bytes *b, bool binary, vtype type, const double *values, size_t n)
{
    static const size_t sizes[] = { 1, 4, 4, 8, 4, 8 };
    for (size_t i = 0; i < n; i++) {
        if (!binary)
            bytes_printf(b, "%.17g%s", values[i], i + 1 == n ? "\n" : " ");
        else if (type == T_F32)
            bytes_f32(b, (float)values[i], true);
        else if (type == T_F64)
            bytes_f64(b, values[i], true);
        else
            bytes_uint(b, (uint64_t)(int64_t)values[i], sizes[type], true);
    }
    if (binary)
        bytes_printf(b, "\n");
}

static void put_positions(bytes *b, bool binary, vtype type)
{
    double values[9];
    for (int i = 0; i < 9; i++)
        values[i] = (double)X[i / 3][i % 3];
    put(b, binary, type, values, 9);
}

static void put_velocity(bytes *b, bool binary)
{
    double values[9];
    for (int i = 0; i < 9; i++)
        values[i] = (double)V[i / 3][i % 3];
    put(b, binary, T_F32, values, 9);
}

static void put_ids(bytes *b, bool binary)
{
    put(b, binary, T_U32, (const double[]){ IDS[0], IDS[1], IDS[2] }, 3);
}

/* POLYDATA: float points, VERTICES, SCALARS with lookup tables, VECTORS,
 * NORMALS, a LOOKUP_TABLE section and an unrelated FIELD. */
static bytes polydata(bool binary)
{
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, "# vtk DataFile Version 3.0\nparticles, made by hand\n%s\nDATASET POLYDATA\n",
                 binary ? "BINARY" : "ASCII");
    bytes_printf(&b, "POINTS 3 float\n");
    put_positions(&b, binary, T_F32);
    bytes_printf(&b, "VERTICES 3 6\n");
    put(&b, binary, T_I32, (const double[]){ 1, 0, 1, 1, 1, 2 }, 6);
    bytes_printf(&b, "POINT_DATA 3\nSCALARS pressure double\nLOOKUP_TABLE my_table\n");
    put(&b, binary, T_F64, (const double[]){ 1, 2, 3 }, 3);
    bytes_printf(&b, "SCALARS Density float 1\nLOOKUP_TABLE default\n");
    put(&b, binary, T_F32, DENSITY, 3);
    bytes_printf(&b, "VECTORS velocity float\n");
    put_velocity(&b, binary);
    bytes_printf(&b, "NORMALS v float\n");
    put(&b, binary, T_F32, (const double[]){ 0, 0, 1, 0, 0, 1, 0, 0, 1 }, 9);
    bytes_printf(&b, "SCALARS id unsigned_int 1\nLOOKUP_TABLE default\n");
    put_ids(&b, binary);
    bytes_printf(&b, "LOOKUP_TABLE my_table 2\n");
    put(&b, binary, binary ? T_U8 : T_F32, (const double[]){ 0, 0, 0, 1, 1, 1, 1, 1 }, 8);
    bytes_printf(&b, "FIELD extra 1\ntemperature 1 3 float\n");
    put(&b, binary, T_F32, (const double[]){ 300, 301, 302 }, 3);
    return b;
}

/* UNSTRUCTURED_GRID: dataset FIELD, double points, cells (legacy or 5.1
 * OFFSETS/CONNECTIVITY), CELL_DATA with a density that must not be taken, then
 * the particle data as FIELD arrays with a METADATA block. */
static bytes grid(bool binary, bool v51)
{
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, "# vtk DataFile Version %s\ngrid\n%s\n\nDATASET UNSTRUCTURED_GRID\n", v51 ? "5.1" : "2.0",
                 binary ? "BINARY" : "ASCII");
    bytes_printf(&b, "FIELD FieldData 1\nTIME 1 1 double\n");
    put(&b, binary, T_F64, (const double[]){ 0.5 }, 1);
    bytes_printf(&b, "POINTS 3 double\n");
    put_positions(&b, binary, T_F64);
    if (v51) {
        bytes_printf(&b, "CELLS 2 3\nOFFSETS vtktypeint64\n");
        put(&b, binary, T_I64, (const double[]){ 0, 3 }, 2);
        bytes_printf(&b, "CONNECTIVITY vtktypeint64\n");
        put(&b, binary, T_I64, (const double[]){ 0, 1, 2 }, 3);
    } else {
        bytes_printf(&b, "CELLS 1 4\n");
        put(&b, binary, T_I32, (const double[]){ 3, 0, 1, 2 }, 4);
    }
    bytes_printf(&b, "CELL_TYPES 1\n");
    put(&b, binary, T_I32, (const double[]){ 5 }, 1);
    bytes_printf(&b, "CELL_DATA 1\nSCALARS density float\nLOOKUP_TABLE default\n");
    put(&b, binary, T_F32, (const double[]){ -5 }, 1);
    bytes_printf(&b, "POINT_DATA 3\nFIELD FieldData 4\nrho 1 3 double\n");
    put(&b, binary, T_F64, DENSITY, 3);
    bytes_printf(&b, "vel 3 3 float\n");
    put_velocity(&b, binary);
    bytes_printf(&b, "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 10\n\n");
    bytes_printf(&b, "NULL_ARRAY\nIDS 1 3 unsigned_int\n");
    put_ids(&b, binary);
    return b;
}

/* As SPlisHSPlasH's VTK exporter writes: version 4.1, BINARY, UNSTRUCTURED_GRID of
 * vertex cells, the particle data as FIELD arrays (id, velocity, density). */
static bytes splishsplash(void)
{
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, "# vtk DataFile Version 4.1\nSPlisHSPlasH particle data\nBINARY\nDATASET UNSTRUCTURED_GRID\n");
    bytes_printf(&b, "POINTS 3 float\n");
    put_positions(&b, true, T_F32);
    bytes_printf(&b, "CELLS 3 6\n");
    put(&b, true, T_I32, (const double[]){ 1, 0, 1, 1, 1, 2 }, 6);
    bytes_printf(&b, "CELL_TYPES 3\n");
    put(&b, true, T_I32, (const double[]){ 1, 1, 1 }, 3);
    bytes_printf(&b, "POINT_DATA 3\nFIELD FieldData 3\nid 1 3 unsigned_int\n");
    put_ids(&b, true);
    bytes_printf(&b, "velocity 3 3 float\n");
    put_velocity(&b, true);
    bytes_printf(&b, "density 1 3 float\n");
    put(&b, true, T_F32, DENSITY, 3);
    return b;
}

/* As DualSPHysics writes its particle VTK: POLYDATA with vertices, the attributes as
 * SCALARS named Idp, Vel (3 components) and Rhop, plus Type and Mk. */
static bytes dualsphysics(bool binary)
{
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, "# vtk DataFile Version 3.0\nDualSPHysics particles\n%s\nDATASET POLYDATA\n",
                 binary ? "BINARY" : "ASCII");
    bytes_printf(&b, "POINTS 3 float\n");
    put_positions(&b, binary, T_F32);
    bytes_printf(&b, "VERTICES 3 6\n");
    put(&b, binary, T_I32, (const double[]){ 1, 0, 1, 1, 1, 2 }, 6);
    bytes_printf(&b, "POINT_DATA 3\nSCALARS Idp unsigned_int\nLOOKUP_TABLE default\n");
    put_ids(&b, binary);
    bytes_printf(&b, "SCALARS Vel float 3\nLOOKUP_TABLE default\n");
    put_velocity(&b, binary);
    bytes_printf(&b, "SCALARS Rhop float\nLOOKUP_TABLE default\n");
    put(&b, binary, T_F32, DENSITY, 3);
    bytes_printf(&b, "SCALARS Type unsigned_char\nLOOKUP_TABLE default\n");
    put(&b, binary, T_U8, (const double[]){ 3, 3, 0 }, 3);
    bytes_printf(&b, "SCALARS Mk unsigned_char\nLOOKUP_TABLE default\n");
    put(&b, binary, T_U8, (const double[]){ 11, 11, 1 }, 3);
    return b;
}

static void check_particles(const bytes *b, const char *what)
{
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles_mem(b->data, b->len, FC_FILE_VTK, what, &frame, &err) == FC_OK, "%s: %s", what,
              err.message);
    CHECK_MSG(frame.count == 3 && frame.density && frame.velocity && frame.ids, "%s: attributes missing", what);
    if (frame.count == 3 && frame.density && frame.velocity && frame.ids) {
        for (int i = 0; i < 3; i++) {
            check_position(&frame, (uint64_t)i, X[i][0], X[i][1], X[i][2]);
            check_velocity(&frame, (uint64_t)i, V[i][0], V[i][1], V[i][2]);
            CHECK_MSG(frame.density[i] == (float)DENSITY[i], "%s: density[%d] = %g", what, i, frame.density[i]);
            CHECK_MSG(frame.ids[i] == IDS[i], "%s: ids[%d] = %u", what, i, frame.ids[i]);
        }
    }
    fc_frame_free(&frame);
}

static void test_good_files(void)
{
    for (int binary = 0; binary < 2; binary++) {
        bytes b = polydata(binary);
        check_particles(&b, binary ? "polydata-binary.vtk" : "polydata-ascii.vtk");
        bytes_free(&b);
        for (int v51 = 0; v51 < 2; v51++) {
            b = grid(binary, v51);
            check_particles(&b, binary ? "grid-binary.vtk" : "grid-ascii.vtk");
            bytes_free(&b);
        }
    }
}

static void test_writers_layouts(void)
{
    bytes b = splishsplash();
    check_particles(&b, "ParticleData_Fluid_1.vtk");
    bytes_free(&b);
    for (int binary = 0; binary < 2; binary++) {
        b = dualsphysics(binary);
        check_particles(&b, binary ? "PartFluid_0001-binary.vtk" : "PartFluid_0001-ascii.vtk");
        bytes_free(&b);
    }
}

static void test_positions_only(void)
{
    const char *text = "# vtk DataFile Version 3.0\nonly points\nascii\ndataset polydata\n"
                       "points 2 int\n1 2 3\n-4 5 -6\n";
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles_mem((const uint8_t *)text, strlen(text), FC_FILE_VTK, "p.vtk", &frame, &err) == FC_OK,
              "%s", err.message);
    CHECK(frame.count == 2 && !frame.density && !frame.velocity && !frame.ids);
    if (frame.count == 2) {
        check_position(&frame, 0, 1, 2, 3);
        check_position(&frame, 1, -4, 5, -6);
    }
    fc_frame_free(&frame);
}

/* The ASCII polydata file with `from` replaced by `to`. */
static bytes polydata_variant(const char *from, const char *to)
{
    bytes good = polydata(false), b = { NULL, 0, 0 };
    bytes_append(&good, "", 1);
    const char *text = (const char *)good.data, *at = strstr(text, from);
    if (at == NULL) {
        fprintf(stderr, "test bug: '%s' not in the polydata file\n", from);
        exit(2);
    }
    bytes_append(&b, text, (size_t)(at - text));
    bytes_append(&b, to, strlen(to));
    bytes_append(&b, at + strlen(from), strlen(at + strlen(from)));
    bytes_free(&good);
    return b;
}

static void expect_variant_failure(const char *from, const char *to, const char *needle)
{
    bytes b = polydata_variant(from, to);
    expect_failure(&b, FC_FILE_VTK, "broken.vtk", FC_ERR_PARSE, needle);
    bytes_free(&b);
}

static void test_ascii_errors(void)
{
    expect_variant_failure("# vtk DataFile", "# vtx DataFile", "line 1: not a legacy VTK file");
    expect_variant_failure("ASCII", "TEXT", "line 3: expected ASCII or BINARY");
    expect_variant_failure("POLYDATA", "STRUCTURED_POINTS", "line 4: DATASET STRUCTURED_POINTS is not supported");
    expect_variant_failure("POINTS 3 float", "POINTS 3 bit", "line 5: unsupported data type 'bit'");
    expect_variant_failure("POINTS 3 float", "POINTS three float", "point count 'three'");
    expect_variant_failure("-1.25", "-1.2.5", "line 6: '-1.2.5' is not a number");
    expect_variant_failure("-1.25", "nan", "line 6: particle 0: y = nan");
    expect_variant_failure("POINT_DATA 3", "POINT_DATA 4", "POINT_DATA 4 does not match POINTS 3");
    expect_variant_failure("VERTICES 3 6", "VERTICES 3 5", "unknown keyword '2'");
    expect_variant_failure("VERTICES 3 6", "VERTICES 3 600", "expected 600 values, found");
    expect_variant_failure("NORMALS", "BLOBS", "unknown keyword 'BLOBS'");
    expect_variant_failure("SCALARS id unsigned_int 1", "SCALARS rho unsigned_int 1", "second array for density ('rho')");
    expect_variant_failure("4294967295", "4294967296", "particle 1: id = 4.29497e+09 is not an integer");
    expect_variant_failure("POINT_DATA 3", "POINTS 3 float\n0 0 0 0 0 0 0 0 0\nPOINT_DATA 3", "second POINTS section");
    expect_text_failure("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINT_DATA 0\n", FC_FILE_VTK,
                        "early.vtk", "POINT_DATA before POINTS");
    expect_text_failure("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nVERTICES 0 0\n", FC_FILE_VTK,
                        "nopoints.vtk", "no POINTS section");
    expect_text_failure("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n", FC_FILE_VTK,
                        "zero.vtk", "no particles");
    expect_text_failure("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nSCALARS a float\n", FC_FILE_VTK,
                        "outside.vtk", "SCALARS outside POINT_DATA or CELL_DATA");
    expect_text_failure("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 2 float\n0 0 0 1 1 1\n"
                        "POINT_DATA 2\nFIELD f 1\nrho 1 1 float\n5\n",
                        FC_FILE_VTK, "tuples.vtk", "line 9: array 'rho' has 1 tuples for 2 points");
    expect_text_failure("# vtk DataFile Version 3.0\nt\n", FC_FILE_VTK, "short.vtk",
                        "header ends before the ASCII/BINARY line");
}

static void test_binary_errors(void)
{
    /* 10^12 points of 4 bytes cannot be in the file: refused by the scan, nothing allocated. */
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET POLYDATA\nPOINTS 1000000000000 float\n");
    put(&b, true, T_F32, (const double[]){ 1, 2, 3 }, 3);
    expect_failure(&b, FC_FILE_VTK, "huge.vtk", FC_ERR_PARSE, "3000000000000 values of 4 bytes run past the end");
    bytes_free(&b);

    b = polydata(true);
    const char *points = strstr((const char *)b.data, "POINTS 3 float\n");
    size_t at = (size_t)(points - (const char *)b.data) + strlen("POINTS 3 float\n") + 4 * 4;
    memcpy(b.data + at, (const uint8_t[]){ 0xff, 0x80, 0x00, 0x00 }, 4);
    char needle[64];
    snprintf(needle, sizeof needle, "byte offset %zu: particle 1: y = -inf", at);
    expect_failure(&b, FC_FILE_VTK, "inf.vtk", FC_ERR_PARSE, needle);
    bytes_free(&b);
}

/* A file cut after any complete section is itself valid, so only cuts before
 * the end of the POINTS values must fail: before the newline that ends them
 * (binary) or inside the last coordinate "30" (ascii). */
static size_t points_end(const bytes *b, const char *next_section, bool binary)
{
    size_t n = strlen(next_section), at = 0;
    while (at + n <= b->len && memcmp(b->data + at, next_section, n) != 0)
        at++;
    return at - (binary ? 1 : 3);
}

static void test_truncations_and_mutations(void)
{
    for (int binary = 0; binary < 2; binary++) {
        bytes b = polydata(binary);
        check_truncations(&b, FC_FILE_VTK, points_end(&b, "\nVERTICES", binary), 3);
        check_mutations(&b, FC_FILE_VTK, 3000, 5u + (uint32_t)binary);
        bytes_free(&b);
        b = grid(binary, true);
        check_truncations(&b, FC_FILE_VTK, points_end(&b, "\nCELLS", binary), 3);
        check_mutations(&b, FC_FILE_VTK, 3000, 7u + (uint32_t)binary);
        bytes_free(&b);
    }
}

int main(void)
{
    test_good_files();
    test_writers_layouts();
    test_positions_only();
    test_ascii_errors();
    test_binary_errors();
    test_truncations_and_mutations();
    return test_result();
}
