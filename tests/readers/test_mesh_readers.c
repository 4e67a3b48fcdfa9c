/* test_mesh_readers.c — the mesh readers (client/meshes): OBJ, STL (binary and
 * ascii), PLY with faces (ascii, binary little- and big-endian) and legacy VTK
 * POLYDATA (ascii and binary, 4.x and 5.1 cell layouts) and VTK XML PolyData
 * (.vtp: ascii and appended raw built here; ascii, base64 binary, appended
 * zlib and appended base64 written by VTK's vtkXMLPolyDataWriter into
 * $FC_VTP_MESH_FIXTURES by make_vtp_mesh_fixtures.py), each file built byte
 * by byte here, read to exact vertices and triangles (polygons fanned, strips
 * wound alike, OBJ's negative indices). Hostile inputs: a table of broken
 * files per format, each refused with FC_ERR_PARSE (or LIMIT) and a message
 * naming the file and the problem; every truncation and 2000 random byte
 * mutations of each good file never crash and never return a mesh whose
 * indices run past its vertices or whose coordinates are not finite. */
#include <math.h>

#include "mesh_reader.h"
#include "readers/reader_test_support.h"

/* The unit quad 0-1-2-3 in z = 0 and a triangle 1-4-2 above it. */
static const float quad_vertices[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0.5f, 1};
static const uint32_t quad_triangles[9] = {0, 1, 2, 0, 2, 3, 1, 4, 2};

static fc_code read_bytes(const char *name, const bytes *b, fc_mesh_data *m, fc_error *err)
{
    /* An exact-size heap copy: a read past the end leaves the allocation (ASan). */
    uint8_t *copy = malloc(b->len ? b->len : 1);
    if (b->len > 0)
        memcpy(copy, b->data, b->len);
    fc_code code = fc_read_mesh_mem(name, copy, b->len, m, err);
    free(copy);
    return code;
}

static void check_mesh(const char *what, const fc_mesh_data *m, const float *vertices, uint32_t vertex_count,
                       const uint32_t *triangles, uint32_t triangle_count)
{
    CHECK_MSG(m->vertex_count == vertex_count && m->triangle_count == triangle_count, "%s: %u vertices %u triangles",
              what, m->vertex_count, m->triangle_count);
    if (m->vertex_count != vertex_count || m->triangle_count != triangle_count)
        return;
    CHECK_MSG(memcmp(m->vertices, vertices, 12 * (size_t)vertex_count) == 0, "%s: vertices differ", what);
    CHECK_MSG(memcmp(m->indices, triangles, 12 * (size_t)triangle_count) == 0, "%s: triangles differ", what);
}

static void expect_read(const char *name, const bytes *b, const float *vertices, uint32_t vertex_count,
                        const uint32_t *triangles, uint32_t triangle_count)
{
    fc_mesh_data m;
    fc_error err;
    fc_code code = read_bytes(name, b, &m, &err);
    CHECK_MSG(code == FC_OK, "%s: %s", name, err.message);
    if (code == FC_OK)
        check_mesh(name, &m, vertices, vertex_count, triangles, triangle_count);
    fc_mesh_data_free(&m);
}

static void expect_refused(const char *name, const char *text, fc_code expected, const char *needle)
{
    bytes b = {0};
    bytes_append(&b, text, strlen(text));
    fc_mesh_data m;
    fc_error err = {FC_OK, ""};
    fc_code code = read_bytes(name, &b, &m, &err);
    CHECK_MSG(code == expected && strstr(err.message, name) && strstr(err.message, needle),
              "%s: got %d \"%s\", want %d mentioning \"%s\"", name, (int)code, err.message, (int)expected, needle);
    CHECK(m.vertices == NULL && m.indices == NULL);
    fc_mesh_data_free(&m);
    bytes_free(&b);
}

/* A mesh a reader returned: indices inside, coordinates finite, at least one triangle. */
static bool mesh_is_sound(const fc_mesh_data *m)
{
    if (m->triangle_count == 0 || m->vertex_count == 0)
        return false;
    for (size_t i = 0; i < 3 * (size_t)m->triangle_count; i++)
        if (m->indices[i] >= m->vertex_count)
            return false;
    for (size_t i = 0; i < 3 * (size_t)m->vertex_count; i++)
        if (!isfinite(m->vertices[i]))
            return false;
    return true;
}

/* Every truncation and random mutations: typed refusals or sound meshes, never a crash. */
static void sweep(const char *name, const bytes *good)
{
    int bad = 0;
    for (size_t n = 0; n <= good->len; n++) {
        bytes cut = {0};
        if (n > 0)
            bytes_append(&cut, good->data, n);
        fc_mesh_data m;
        fc_error err;
        fc_code code = read_bytes(name, &cut, &m, &err);
        bad += code == FC_OK ? !mesh_is_sound(&m) : !(code == FC_ERR_PARSE || code == FC_ERR_LIMIT);
        fc_mesh_data_free(&m);
        bytes_free(&cut);
    }
    uint32_t seed = 12345u;
    for (int i = 0; i < 2000; i++) {
        bytes mutated = {0};
        bytes_append(&mutated, good->data, good->len);
        for (int k = 0; k < 1 + i % 4; k++) {
            seed = seed * 1664525u + 1013904223u;
            mutated.data[(seed >> 8) % mutated.len] = (uint8_t)(seed >> 24);
        }
        fc_mesh_data m;
        fc_error err;
        fc_code code = read_bytes(name, &mutated, &m, &err);
        bad += code == FC_OK ? !mesh_is_sound(&m) : !(code == FC_ERR_PARSE || code == FC_ERR_LIMIT);
        fc_mesh_data_free(&m);
        bytes_free(&mutated);
    }
    CHECK_MSG(bad == 0, "%s: %d truncations or mutations gave an unsound mesh or an untyped error", name, bad);
}

/* ---- OBJ ---- */

static void test_obj(void)
{
    bytes b = {0};
    bytes_printf(&b, "# a quad and a triangle\r\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0\n"
                     "vt 0 0\nvn 0 0 1\ns off\nf 1/1/1 2/1/1 3//1 4\nv 2 0.5 1\nf -4 -1 -3\n");
    expect_read("quad.obj", &b, quad_vertices, 5, quad_triangles, 3);
    sweep("quad.obj", &b);
    bytes_free(&b);
    expect_refused("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", FC_ERR_PARSE, "line 4");
    expect_refused("past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", FC_ERR_PARSE, "vertex 3, but there are 3");
    expect_refused("back.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n", FC_ERR_PARSE, "counts back");
    expect_refused("short.obj", "v 0 0\n", FC_ERR_PARSE, "three numbers");
    expect_refused("nan.obj", "v 0 nan 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", FC_ERR_PARSE, "not a finite");
    expect_refused("huge.obj", "v 0 1e39 0\n", FC_ERR_PARSE, "not a finite");
    expect_refused("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", FC_ERR_PARSE, "2 corners");
    expect_refused("word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 two 3\n", FC_ERR_PARSE, "\"two\"");
    expect_refused("points.obj", "v 0 0 0\nv 1 0 0\n", FC_ERR_PARSE, "no triangles");
}

/* ---- STL ---- */

static void stl_binary(bytes *b, const float (*tris)[9], uint32_t count, uint32_t claimed)
{
    uint8_t header[80] = "solid but binary";
    bytes_append(b, header, 80);
    bytes_uint(b, claimed, 4, false);
    for (uint32_t t = 0; t < count; t++) {
        for (int k = 0; k < 3; k++)
            bytes_f32(b, 0.0f, false);
        for (int k = 0; k < 9; k++)
            bytes_f32(b, tris[t][k], false);
        bytes_uint(b, 0, 2, false);
    }
}

static void test_stl(void)
{
    static const float tris[2][9] = {{0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 0, 1, 1, 0, 0, 1, 0}};
    static const float expected_vertices[18] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};
    static const uint32_t expected_triangles[6] = {0, 1, 2, 3, 4, 5};
    bytes b = {0};
    stl_binary(&b, tris, 2, 2);
    expect_read("quad.stl", &b, expected_vertices, 6, expected_triangles, 2);
    sweep("quad.stl", &b);
    bytes_free(&b);

    stl_binary(&b, tris, 2, 3);   /* claims 3: the size says otherwise */
    fc_mesh_data m;
    fc_error err;
    CHECK_CODE(read_bytes("claims.stl", &b, &m, &err), FC_ERR_PARSE);
    CHECK(strstr(err.message, "needs 234 bytes") != NULL);
    bytes_free(&b);
    float nan_tri[1][9] = {{0, 0, 0, NAN, 0, 0, 1, 1, 0}};
    stl_binary(&b, (const float(*)[9])nan_tri, 1, 1);
    CHECK_CODE(read_bytes("nan.stl", &b, &m, &err), FC_ERR_PARSE);
    bytes_free(&b);

    bytes_printf(&b, "solid quad\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                     "   vertex 1 1 0\n  endloop\n endfacet\n FACET NORMAL 0 0 1\n  OUTER LOOP\n   VERTEX 0 0 0\n"
                     "   VERTEX 1 1 0\n   VERTEX 0 1 0\n  ENDLOOP\n ENDFACET\nendsolid quad\n");
    expect_read("ascii.stl", &b, expected_vertices, 6, expected_triangles, 2);
    sweep("ascii.stl", &b);
    bytes_free(&b);
    expect_refused("noloop.stl", "solid a\nfacet normal 0 0 1\nvertex 0 0 0\n", FC_ERR_PARSE, "\"outer\"");
    expect_refused("open.stl", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n",
                   FC_ERR_PARSE, "ends inside a facet");
    expect_refused("bad.stl", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 x 0\n", FC_ERR_PARSE,
                   "3 numbers");
    expect_refused("what.stl", "hello\n", FC_ERR_PARSE, "neither a binary STL");
    expect_refused("empty.stl", "solid a\nendsolid a\n", FC_ERR_PARSE, "no triangles");
}

/* ---- PLY ---- */

static void ply_binary(bytes *b, bool big)
{
    bytes_printf(&b[0], "ply\nformat %s 1.0\ncomment made here\nelement vertex 5\nproperty float x\n"
                        "property double confidence\nproperty float y\nproperty float z\nelement face 2\n"
                        "property list uchar int vertex_indices\nproperty uchar flags\nelement edge 1\n"
                        "property list uchar uint vertex_index\nend_header\n",
                 big ? "binary_big_endian" : "binary_little_endian");
    for (int v = 0; v < 5; v++) {
        bytes_f32(b, quad_vertices[3 * v], big);
        bytes_f64(b, 0.5, big);
        bytes_f32(b, quad_vertices[3 * v + 1], big);
        bytes_f32(b, quad_vertices[3 * v + 2], big);
    }
    bytes_uint(b, 4, 1, big);
    for (int i = 0; i < 4; i++)
        bytes_uint(b, (uint64_t)i, 4, big);
    bytes_uint(b, 7, 1, big);
    bytes_uint(b, 3, 1, big);
    bytes_uint(b, 1, 4, big), bytes_uint(b, 4, 4, big), bytes_uint(b, 2, 4, big);
    bytes_uint(b, 0, 1, big);
    bytes_uint(b, 2, 1, big);
    bytes_uint(b, 0, 4, big), bytes_uint(b, 1, 4, big);
}

static void test_ply(void)
{
    bytes b = {0};
    bytes_printf(&b, "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                     "property float z\nproperty uchar red\nelement face 2\nproperty list uchar int vertex_index\n"
                     "end_header\n0 0 0 255\n1 0 0 0\n1 1 0 0\n0 1 0 0\n2 0.5 1 9\n4 0 1 2 3\n3 1 4 2\n");
    expect_read("ascii.ply", &b, quad_vertices, 5, quad_triangles, 3);
    sweep("ascii.ply", &b);
    bytes_free(&b);
    for (int big = 0; big <= 1; big++) {
        ply_binary(&b, big);
        const char *name = big ? "big.ply" : "little.ply";
        expect_read(name, &b, quad_vertices, 5, quad_triangles, 3);
        sweep(name, &b);
        bytes_free(&b);
    }
    const char *head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    char text[1024];
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", head);
    expect_refused("past.ply", text, FC_ERR_PARSE, "vertex 3, but there are 3");
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1 0\n3 0 1\n", head);
    expect_refused("short.ply", text, FC_ERR_PARSE, "ends early");
    snprintf(text, sizeof text, "%s0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", head);
    expect_refused("inf.ply", text, FC_ERR_PARSE, "not a finite");
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1 0\n9999 0 1 2\n", head);
    expect_refused("long.ply", text, FC_ERR_PARSE, "a list of 9999");
    expect_refused("nox.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nend_header\n0\n",
                   FC_ERR_PARSE, "lacks x");
    expect_refused("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", FC_ERR_PARSE, "end_header");
    expect_refused("many.ply", "ply\nformat ascii 1.0\nelement vertex 99999999\nproperty float x\nproperty float y\n"
                   "property float z\nend_header\n", FC_ERR_LIMIT, "exceed");
    expect_refused("noface.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                   "property float z\nend_header\n0 0 0\n", FC_ERR_PARSE, "no triangles");
}

/* ---- VTK ---- */

static void vtk_binary(bytes *b)
{
    bytes_printf(b, "# vtk DataFile Version 4.2\nquad\nBINARY\nDATASET POLYDATA\nPOINTS 5 float\n");
    for (int i = 0; i < 15; i++)
        bytes_f32(b, quad_vertices[i], true);
    bytes_printf(b, "\nPOLYGONS 2 9\n");
    const uint32_t cells[9] = {4, 0, 1, 2, 3, 3, 1, 4, 2};
    for (int i = 0; i < 9; i++)
        bytes_uint(b, cells[i], 4, true);
    bytes_printf(b, "\nPOINT_DATA 5\nSCALARS s float 1\nLOOKUP_TABLE default\n");
}

static void test_vtk(void)
{
    bytes b = {0};
    bytes_printf(&b, "# vtk DataFile Version 3.0\nquad\nASCII\nDATASET POLYDATA\nPOINTS 5 float\n0 0 0 1 0 0\n"
                     "1 1 0 0 1 0 2 0.5 1\nVERTICES 1 2\n1 4\nPOLYGONS 2 9\n4 0 1 2 3\n3 1 4 2\n"
                     "POINT_DATA 5\nSCALARS p float\nLOOKUP_TABLE default\n0 0 0 0 0\n");
    expect_read("ascii.vtk", &b, quad_vertices, 5, quad_triangles, 3);
    sweep("ascii.vtk", &b);
    bytes_free(&b);
    vtk_binary(&b);
    expect_read("binary.vtk", &b, quad_vertices, 5, quad_triangles, 3);
    sweep("binary.vtk", &b);
    bytes_free(&b);
    /* 5.1: OFFSETS and CONNECTIVITY, a METADATA block. */
    bytes_printf(&b, "# vtk DataFile Version 5.1\nquad\nASCII\nDATASET POLYDATA\nPOINTS 5 float\n"
                     "0 0 0 1 0 0 1 1 0 0 1 0 2 0.5 1\nMETADATA\nINFORMATION 0\n\nPOLYGONS 3 7\n"
                     "OFFSETS vtktypeint64\n0 4 7\nCONNECTIVITY vtktypeint64\n0 1 2 3 1 4 2\n");
    expect_read("offsets.vtk", &b, quad_vertices, 5, quad_triangles, 3);
    sweep("offsets.vtk", &b);
    bytes_free(&b);
    /* A strip 0 1 3 2 of the quad: triangles 0-1-3 and 3-1-2 (the second reversed to keep the winding). */
    static const uint32_t strip_triangles[6] = {0, 1, 3, 3, 1, 2};
    bytes_printf(&b, "# vtk DataFile Version 4.2\nstrip\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n"
                     "0 0 0 1 0 0 1 1 0 0 1 0\nTRIANGLE_STRIPS 1 5\n4 0 1 3 2\n");
    expect_read("strip.vtk", &b, quad_vertices, 4, strip_triangles, 2);
    bytes_free(&b);
    expect_refused("grid.vtk", "# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n", FC_ERR_PARSE,
                   "POLYDATA");
    expect_refused("past.vtk", "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n"
                   "0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 7\n", FC_ERR_PARSE, "vertex 7");
    expect_refused("size.vtk", "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n"
                   "0 0 0 1 0 0 0 1 0\nPOLYGONS 1 5\n3 0 1 2\n", FC_ERR_PARSE, "size says 5");
    expect_refused("cut.vtk", "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1\n",
                   FC_ERR_PARSE, "ends early");
    expect_refused("order.vtk", "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOLYGONS 1 4\n3 0 1 2\n",
                   FC_ERR_PARSE, "before POINTS");
    expect_refused("offsets.vtk", "# vtk DataFile Version 5.1\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n"
                   "0 0 0 1 0 0 0 1 0\nPOLYGONS 2 3\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n0 1 2\n",
                   FC_ERR_PARSE, "offset");
    expect_refused("many.vtk", "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOINTS 99999999 float\n",
                   FC_ERR_LIMIT, "exceed");
    expect_refused("nothing.vtk", "hello\n", FC_ERR_PARSE, "not a legacy VTK");
}

/* ---- VTK XML PolyData (.vtp) ---- */

static const char vtp_head[] =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    "<PolyData>\n<Piece NumberOfPoints=\"5\" NumberOfPolys=\"2\" NumberOfStrips=\"0\">\n"
    "<PointData Normals=\"Normals\"><DataArray type=\"Float32\" Name=\"Normals\" NumberOfComponents=\"3\" "
    "format=\"ascii\">0 0 1 0 0 1 0 0 1 0 0 1 0 0 1</DataArray></PointData>\n";

static void vtp_ascii(bytes *b, const char *offsets, const char *connectivity)
{
    bytes_printf(b, "%s<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
                    "0 0 0 1 0 0 1 1 0 0 1 0 2 0.5 1</DataArray></Points>\n<Polys>\n"
                    "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">%s</DataArray>\n"
                    "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">%s</DataArray>\n"
                    "</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n", vtp_head, connectivity, offsets);
}

/* The ascii mesh with other cells, refused with `needle` in the message. */
static void vtp_refused(const char *name, const char *offsets, const char *connectivity, const char *needle)
{
    bytes b = {0};
    vtp_ascii(&b, offsets, connectivity);
    bytes_append(&b, "", 1); /* a C string for expect_refused */
    expect_refused(name, (const char *)b.data, FC_ERR_PARSE, needle);
    bytes_free(&b);
}

/* The same mesh with its arrays appended raw: UInt32 headers, float points, Int64 cells. */
static void vtp_appended(bytes *b)
{
    bytes_printf(b, "%s<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/>"
                    "</Points>\n<Polys>\n"
                    "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"64\"/>\n"
                    "<DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"124\"/>\n"
                    "</Polys>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_", vtp_head);
    bytes_uint(b, 60, 4, false);
    for (int i = 0; i < 15; i++)
        bytes_f32(b, quad_vertices[i], false);
    bytes_uint(b, 56, 4, false);
    const uint64_t connectivity[7] = {0, 1, 2, 3, 1, 4, 2}, offsets[2] = {4, 7};
    for (int i = 0; i < 7; i++)
        bytes_uint(b, connectivity[i], 8, false);
    bytes_uint(b, 16, 4, false);
    for (int i = 0; i < 2; i++)
        bytes_uint(b, offsets[i], 8, false);
    bytes_printf(b, "\n</AppendedData>\n</VTKFile>\n");
}

static bool load_file(const char *path, bytes *b)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return false;
    uint8_t chunk[4096];
    size_t got;
    while ((got = fread(chunk, 1, sizeof chunk, f)) > 0)
        bytes_append(b, chunk, got);
    fclose(f);
    return true;
}

/* The files VTK's writer made: exact triangles in every mode, the strips-only one refused. */
static void test_vtp_fixtures(const char *dir)
{
    static const char *const files[] = {"ascii.vtp", "binary_zlib.vtp", "appended_zlib.vtp", "appended_base64.vtp"};
    char path[512];
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        bytes b = {0};
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        if (!load_file(path, &b)) {
            printf("no VTK-written %s (python3-vtk9 missing?): byte-built .vtp files only\n", path);
            return;
        }
        expect_read(files[i], &b, quad_vertices, 5, quad_triangles, 3);
        if (i == 2)
            sweep(files[i], &b);
        bytes_free(&b);
    }
    bytes b = {0};
    snprintf(path, sizeof path, "%s/strips.vtp", dir);
    CHECK(load_file(path, &b));
    fc_mesh_data m;
    fc_error err = {FC_OK, ""};
    fc_code code = read_bytes("strips.vtp", &b, &m, &err);
    CHECK_MSG(code == FC_ERR_PARSE && strstr(err.message, "no Polys") && strstr(err.message, "1 strips"),
              "strips.vtp: %d %s", (int)code, err.message);
    bytes_free(&b);
}

static void test_vtp(void)
{
    bytes b = {0};
    vtp_ascii(&b, "4 7", "0 1 2 3 1 4 2");
    expect_read("ascii.vtp", &b, quad_vertices, 5, quad_triangles, 3);
    sweep("ascii.vtp", &b);
    bytes_free(&b);
    vtp_appended(&b);
    expect_read("raw.vtp", &b, quad_vertices, 5, quad_triangles, 3);
    sweep("raw.vtp", &b);
    bytes_free(&b);

    vtp_refused("order.vtp", "4 3", "0 1 2 3 1 4 2", "offsets[1]");
    vtp_refused("past.vtp", "4 7", "0 1 2 3 1 9 2", "not a point index");
    vtp_refused("short.vtp", "4 8", "0 1 2 3 1 4 2", "connectivity");
    vtp_refused("two.vtp", "2 7", "0 1 2 3 1 4 2", "at least 3");
    expect_refused("lines.vtp", "<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"2\" NumberOfLines=\"1\">"
                   "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 1 1"
                   "</DataArray></Points></Piece></PolyData></VTKFile>", FC_ERR_PARSE, "1 lines");
    expect_refused("pieces.vtp", "<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"0\"/>"
                   "<Piece NumberOfPoints=\"0\"/></PolyData></VTKFile>", FC_ERR_PARSE, "second Piece");
    expect_refused("grid.vtp", "<VTKFile type=\"UnstructuredGrid\"/>", FC_ERR_PARSE, "not PolyData");
    expect_refused("nothing.vtp", "hello", FC_ERR_PARSE, "XML");
    const char *fixtures = getenv("FC_VTP_MESH_FIXTURES");
    if (fixtures)
        test_vtp_fixtures(fixtures);
    else
        printf("FC_VTP_MESH_FIXTURES not set: byte-built .vtp files only\n");
}

static void test_dispatch(void)
{
    fc_mesh_data m;
    fc_error err;
    CHECK_CODE(fc_read_mesh_mem("x.txt", (const uint8_t *)"", 0, &m, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_read_mesh("/nonexistent/dir/x.obj", &m, &err), FC_ERR_IO);
    CHECK(fc_mesh_format_from_path("A.OBJ") == FC_MESH_FILE_OBJ && fc_mesh_format_from_path("b.Stl") ==
          FC_MESH_FILE_STL);
    CHECK(fc_mesh_format_from_path("tank.VTP") == FC_MESH_FILE_VTP);
}

int main(void)
{
    test_obj();
    test_stl();
    test_ply();
    test_vtk();
    test_vtp();
    test_dispatch();
    return test_result();
}
