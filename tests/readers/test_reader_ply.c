/* test_reader_ply.c — PLY ascii / binary little / binary big endian: exact values
 * for every attribute, elements and list properties before and after the
 * vertices, other scalar types, and broken files of every kind. */
#include "reader_test_support.h"

/* The three particles every good test file holds. */
static const float X[3][3] = { { 0.5f, -1.25f, 3.0f }, { -0.001f, 2000.0f, 0.015f }, { 10.0f, 20.0f, 30.0f } };
static const double DENSITY[3] = { 1000.5, 998.25, 1001.0 };
static const float V[3][3] = { { 0.125f, -0.25f, 4.0f }, { 0.0f, 0.0f, -9.81f }, { 1.0f, 2.0f, 3.0f } };
static const uint32_t IDS[3] = { 7, 4294967295u, 0 };

static const char *ASCII_PLY =
    "ply\n"
    "format ascii 1.0\n"
    "comment elements before and after the vertices, lists, an unused property\n"
    "obj_info made by hand\n"
    "element camera 1\n"
    "property float fov\n"
    "property list uchar int tags\n"
    "element vertex 3\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "property float nx\n"
    "property double density\n"
    "property float vx\n"
    "property float vy\n"
    "property float vz\n"
    "property uint id\n"
    "element face 2\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "45.0 2 7 8\n"
    "0.5 -1.25 3 0 1000.5 0.125 -0.25 4 7\n"
    "-0.001 2e3 1.5e-2 1 998.25 0 0 -9.81 4294967295\n"
    "10 20 30 0 1001 1 2 3 0\n"
    "3 0 1 2\n"
    "3 2 1 0\n";

static void check_three_particles(const fc_frame *f, bool with_velocity)
{
    CHECK(f->count == 3);
    CHECK(f->positions && f->density && f->ids);
    CHECK(with_velocity ? f->velocity != NULL : f->velocity == NULL);
    if (f->count != 3 || !f->positions || !f->density || !f->ids)
        return;
    for (int i = 0; i < 3; i++) {
        check_position(f, (uint64_t)i, X[i][0], X[i][1], X[i][2]);
        CHECK_MSG(f->density[i] == (float)DENSITY[i], "density[%d] = %g", i, f->density[i]);
        CHECK_MSG(f->ids[i] == IDS[i], "ids[%d] = %u", i, f->ids[i]);
        if (with_velocity && f->velocity)
            check_velocity(f, (uint64_t)i, V[i][0], V[i][1], V[i][2]);
    }
}

static void test_ascii(void)
{
    fc_frame frame;
    fc_error err;
    CHECK_CODE(fc_read_particles_mem((const uint8_t *)ASCII_PLY, strlen(ASCII_PLY), FC_FILE_PLY, "a.ply", &frame, &err),
               FC_OK);
    check_three_particles(&frame, true);
    fc_frame_free(&frame);
}

/* The same particles as ASCII_PLY. The first layout mirrors it; the other one
 * uses other types and names (double positions, float rho, uint32 id), puts
 * the id first and a list property inside the vertex element, and has no velocity. */
static bytes binary_ply(bool big_endian, bool other_layout)
{
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, "ply\r\nformat %s 1.0\r\n", big_endian ? "binary_big_endian" : "binary_little_endian");
    bytes_printf(&b, "element camera 1\nproperty float fov\nproperty list uchar int tags\n");
    if (other_layout)
        bytes_printf(&b, "element vertex 3\nproperty uint32 id\nproperty double x\nproperty double y\n"
                         "property double z\nproperty list ushort short neighbours\nproperty float rho\n"
                         "property uchar red\n");
    else
        bytes_printf(&b, "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                         "property float nx\nproperty double density\nproperty float vx\nproperty float vy\n"
                         "property float vz\nproperty uint id\n");
    bytes_printf(&b, "element face 2\nproperty list uchar int vertex_indices\nend_header\n");
    bytes_f32(&b, 45.0f, big_endian);
    bytes_uint(&b, 2, 1, big_endian);
    bytes_uint(&b, 7, 4, big_endian);
    bytes_uint(&b, 8, 4, big_endian);
    for (int i = 0; i < 3; i++) {
        if (other_layout) {
            bytes_uint(&b, IDS[i], 4, big_endian);
            for (int a = 0; a < 3; a++)
                bytes_f64(&b, (double)X[i][a], big_endian);
            bytes_uint(&b, (uint64_t)i, 2, big_endian); /* i neighbours */
            for (int k = 0; k < i; k++)
                bytes_uint(&b, (uint64_t)(int64_t)-k, 2, big_endian);
            bytes_f32(&b, (float)DENSITY[i], big_endian);
            bytes_uint(&b, 255, 1, big_endian);
        } else {
            for (int a = 0; a < 3; a++)
                bytes_f32(&b, X[i][a], big_endian);
            bytes_f32(&b, 0.0f, big_endian);
            bytes_f64(&b, DENSITY[i], big_endian);
            for (int a = 0; a < 3; a++)
                bytes_f32(&b, V[i][a], big_endian);
            bytes_uint(&b, IDS[i], 4, big_endian);
        }
    }
    for (int face = 0; face < 2; face++) {
        bytes_uint(&b, 3, 1, big_endian);
        for (int k = 0; k < 3; k++)
            bytes_uint(&b, (uint64_t)(face ? 2 - k : k), 4, big_endian);
    }
    return b;
}

static void test_binary(void)
{
    for (int big = 0; big < 2; big++) {
        for (int other = 0; other < 2; other++) {
            bytes b = binary_ply(big, other);
            fc_frame frame;
            fc_error err = { FC_OK, "" };
            CHECK_MSG(fc_read_particles_mem(b.data, b.len, FC_FILE_PLY, "b.ply", &frame, &err) == FC_OK,
                      "big %d, other layout %d: %s", big, other, err.message);
            check_three_particles(&frame, !other);
            fc_frame_free(&frame);
            bytes_free(&b);
        }
    }
}

static void test_scalar_types(void)
{
    /* Integer positions of every width, signed and unsigned, big endian. */
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, "ply\nformat binary_big_endian 1.0\nelement vertex 1\n"
                     "property char x\nproperty short y\nproperty int z\nproperty uchar vx\nproperty ushort vy\n"
                     "property int8 vz\nproperty uint16 id\nend_header\n");
    bytes_uint(&b, (uint64_t)(int64_t)-5, 1, true);
    bytes_uint(&b, (uint64_t)(int64_t)-300, 2, true);
    bytes_uint(&b, (uint64_t)(int64_t)-70000, 4, true);
    bytes_uint(&b, 200, 1, true);
    bytes_uint(&b, 60000, 2, true);
    bytes_uint(&b, (uint64_t)(int64_t)-128, 1, true);
    bytes_uint(&b, 65535, 2, true);
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles_mem(b.data, b.len, FC_FILE_PLY, "t.ply", &frame, &err) == FC_OK, "%s", err.message);
    if (frame.count == 1 && frame.velocity && frame.ids) {
        check_position(&frame, 0, -5.0f, -300.0f, -70000.0f);
        check_velocity(&frame, 0, 200.0f, 60000.0f, -128.0f);
        CHECK(frame.ids[0] == 65535u);
        CHECK(frame.density == NULL);
    }
    fc_frame_free(&frame);
    bytes_free(&b);
}

/* ASCII_PLY with `from` replaced by `to` (first occurrence). */
static char *ascii_variant(const char *from, const char *to)
{
    static char text[4096];
    const char *at = strstr(ASCII_PLY, from);
    if (at == NULL) {
        fprintf(stderr, "test bug: '%s' not in ASCII_PLY\n", from);
        exit(2);
    }
    snprintf(text, sizeof text, "%.*s%s%s", (int)(at - ASCII_PLY), ASCII_PLY, to, at + strlen(from));
    return text;
}

static void test_ascii_errors(void)
{
    const char *message = expect_text_failure(ascii_variant("10 20 30 0 1001 1 2 3 0", "10 20 30 0 1001 1 2 3"),
                                              FC_FILE_PLY, "frame.ply", NULL);
    CHECK_MSG(strcmp(message, "frame.ply: line 24: expected 9 values, found 8") == 0, "got '%s'", message);
    message = expect_text_failure(ascii_variant("3 0 1 2\n", "3 0 1 2 5\n"), FC_FILE_PLY, "frame.ply", NULL);
    CHECK_MSG(strcmp(message, "frame.ply: line 25: expected 4 values, found 5") == 0, "got '%s'", message);
    expect_text_failure(ascii_variant("3 0 1 2\n", "4 0 1 2\n"), FC_FILE_PLY, "list.ply",
                        "line 25: expected 5 values, found 4");
    expect_text_failure(ascii_variant("45.0 2 7 8", "45.0 -1 7 8"), FC_FILE_PLY, "neg.ply",
                        "line 21: list 'tags': count '-1' is not a valid length");
    expect_text_failure(ascii_variant("2e3", "2e3x"), FC_FILE_PLY, "num.ply", "line 23: particle 1: y: '2e3x' is not a number");
    expect_text_failure(ascii_variant("1000.5", "nan"), FC_FILE_PLY, "nan.ply", "line 22: particle 0: density = nan");
    expect_text_failure(ascii_variant("-1.25", "-inf"), FC_FILE_PLY, "inf.ply", "particle 0: y = -inf");
    expect_text_failure(ascii_variant("-1.25", "1e39"), FC_FILE_PLY, "big.ply", "is not a finite value in float range");
    expect_text_failure(ascii_variant("4 7\n", "4 -7\n"), FC_FILE_PLY, "id.ply", "id = -7 is not an integer");
    expect_text_failure(ascii_variant("4 7\n", "4 7.5\n"), FC_FILE_PLY, "id.ply", "id = 7.5 is not an integer");
    expect_text_failure(ascii_variant("4294967295", "4294967296"), FC_FILE_PLY, "id.ply", "is not an integer");
    expect_text_failure(ascii_variant("element face 2", "element face 3"), FC_FILE_PLY, "count.ply",
                        "data ends after 2 of 3 'face' lines");
    expect_text_failure(ascii_variant("element vertex 3", "element vertex 2"), FC_FILE_PLY, "count.ply",
                        "line 24: expected 11 values, found 9");
    expect_text_failure(ascii_variant("3 2 1 0\n", "3 2 1 0\n3 1 1 1\n"), FC_FILE_PLY, "extra.ply",
                        "line 27: unexpected data after the last element");
}

static void test_header_errors(void)
{
    expect_text_failure(ascii_variant("ply\n", "plx\n"), FC_FILE_PLY, "h.ply", "line 1: not a PLY file");
    expect_text_failure(ascii_variant("format ascii 1.0", "format binary_middle_endian 1.0"), FC_FILE_PLY, "h.ply",
                        "line 2: unknown format 'binary_middle_endian'");
    expect_text_failure(ascii_variant("format ascii 1.0", "format ascii 2.0"), FC_FILE_PLY, "h.ply",
                        "unsupported PLY version '2.0'");
    expect_text_failure(ascii_variant("format ascii 1.0\n", ""), FC_FILE_PLY, "h.ply", "no format line");
    expect_text_failure(ascii_variant("property float y\n", ""), FC_FILE_PLY, "h.ply", "x, y and z are required");
    expect_text_failure(ascii_variant("property float vy\n", ""), FC_FILE_PLY, "h.ply", "velocity needs all of vx, vy and vz");
    expect_text_failure(ascii_variant("property float nx", "property float X"), FC_FILE_PLY, "h.ply",
                        "line 12: vertex property 'X' gives x a second time");
    expect_text_failure(ascii_variant("property float nx", "property list uchar float rho"), FC_FILE_PLY, "h.ply",
                        "vertex property 'rho' is a list");
    expect_text_failure(ascii_variant("property float nx", "property float16 nx"), FC_FILE_PLY, "h.ply",
                        "line 12: unknown property type 'float16'");
    expect_text_failure(ascii_variant("element vertex 3", "element vertex three"), FC_FILE_PLY, "h.ply",
                        "element count 'three'");
    expect_text_failure(ascii_variant("element vertex 3", "element points 3"), FC_FILE_PLY, "h.ply", "no vertex element");
    expect_text_failure(ascii_variant("end_header\n", "end_header extra\n"), FC_FILE_PLY, "h.ply", "unexpected 'extra'");
    expect_text_failure(ascii_variant("obj_info", "info"), FC_FILE_PLY, "h.ply", "unknown header keyword 'info'");
    expect_text_failure("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", FC_FILE_PLY, "h.ply",
                        "header ends without end_header");
    expect_text_failure("ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\nend_header\n1\n", FC_FILE_PLY,
                        "h.ply", "line 3: property before any element");
    expect_text_failure("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                        "property float z\nend_header\n",
                        FC_FILE_PLY, "zero.ply", "no particles");
    /* A count the file cannot hold is refused before anything is allocated for it. */
    expect_text_failure("ply\nformat binary_little_endian 1.0\nelement vertex 999999999999999\nproperty float x\n"
                        "property float y\nproperty float z\nend_header\n0123456789ab",
                        FC_FILE_PLY, "huge.ply", "999999999999999 instances cannot fit in the 12 bytes");
}

static void test_binary_errors(void)
{
    bytes b = binary_ply(false, false);
    bytes_uint(&b, 0, 1, false);
    expect_failure(&b, FC_FILE_PLY, "tail.ply", FC_ERR_PARSE, "1 bytes after the last element");
    bytes_free(&b);

    /* NaN in the second particle's z: after the camera (4 + 1 + 2x4) and particle 0 (40). */
    b = binary_ply(true, false);
    const char *end = strstr((const char *)b.data, "end_header\n");
    size_t body = (size_t)(end - (const char *)b.data) + strlen("end_header\n");
    size_t at = body + 13 + 40 + 8;
    memcpy(b.data + at, (const uint8_t[]){ 0x7f, 0xc0, 0x00, 0x00 }, 4);
    char needle[64];
    snprintf(needle, sizeof needle, "byte offset %zu: particle 1: z = nan", at);
    expect_failure(&b, FC_FILE_PLY, "nan.ply", FC_ERR_PARSE, needle);
    bytes_free(&b);

    /* A face list claiming 255 items runs out of data. */
    b = binary_ply(false, false);
    b.data[b.len - 13] = 0xff;
    expect_failure(&b, FC_FILE_PLY, "list.ply", FC_ERR_PARSE, "255 items run past the end of the data");
    bytes_free(&b);
}

static void test_truncations_and_mutations(void)
{
    for (int big = 0; big < 2; big++) {
        bytes b = binary_ply(big, big);
        check_truncations(&b, FC_FILE_PLY, b.len, 3);
        check_mutations(&b, FC_FILE_PLY, 3000, 17u + (uint32_t)big);
        bytes_free(&b);
    }
    bytes a = { NULL, 0, 0 };
    bytes_append(&a, ASCII_PLY, strlen(ASCII_PLY));
    /* Any cut before the last face's final index loses a value. */
    check_truncations(&a, FC_FILE_PLY, a.len - 1, 3);
    check_mutations(&a, FC_FILE_PLY, 3000, 99u);
    bytes_free(&a);
}

int main(void)
{
    test_ascii();
    test_binary();
    test_scalar_types();
    test_ascii_errors();
    test_header_errors();
    test_binary_errors();
    test_truncations_and_mutations();
    return test_result();
}
