/* test_wire_mesh.c — MESH and MESH_TRANSFORM (PROTOCOL.md section 12): the
 * exact bytes of the section's examples, round trips, and every check of
 * 12.1 and 12.2 with its code and the triangle or vertex it names. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "test_util.h"
#include "wire.h"
#include "wire_mesh.h"

static const float triangle_vertices[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
static const uint32_t triangle_indices[3] = {0, 1, 2};

/* Mesh 7: one triangle, orange-ish, hide-near, identity transform. */
static fc_mesh triangle_mesh(void)
{
    fc_mesh m = {.id = 7, .flags = FC_MESH_HIDE_NEAR, .vertex_count = 3, .triangle_count = 1,
                 .vertices = triangle_vertices, .indices = triangle_indices,
                 .color = {1.0f, 0.5f, 0.25f}, .opacity = 1.0f};
    fc_mesh_identity(m.transform);
    return m;
}

/* PROTOCOL.md 12.1's example, byte for byte. */
static const uint8_t example_mesh[] = {
    0x46, 0x43, 0x53, 0x54, 0x0c, 0x00, 0x00, 0x00, 0x09, 0x00, 0x00, 0x00, 0x80, 0x00, 0x00, 0x00,
    0x07, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x80, 0x3e, /* color 1 0.5 0.25 */
    0x00, 0x00, 0x80, 0x3f,                                                 /* opacity 1 */
    0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,             /* transform row 0 */
    0, 0, 0, 0, 0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0, 0, 0, 0, 0,             /* row 1 */
    0, 0, 0, 0, 0, 0, 0, 0, 0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0,             /* row 2 */
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,                                     /* vertex 0 */
    0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0, 0, 0, 0, 0,                         /* vertex 1 */
    0, 0, 0, 0, 0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0,                         /* vertex 2 */
    0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, /* triangle 0 1 2 */
};

/* Reads from an exact-size heap copy, so a read past the end faults under ASan. */
static fc_code read_copy(const uint8_t *p, size_t n, fc_mesh *m, void **storage, fc_error *err)
{
    uint8_t *copy = malloc(n ? n : 1);
    memcpy(copy, p, n);
    fc_code code = fc_wire_read_mesh(copy, n, m, storage, err);
    free(copy);
    return code;
}

static void test_example_bytes(void)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_mesh m = triangle_mesh();
    CHECK_CODE(fc_wire_write_mesh(&b, 9, &m, &err), FC_OK);
    CHECK_MSG(b.len == sizeof example_mesh && memcmp(b.data, example_mesh, sizeof example_mesh) == 0,
              "MESH example: %zu bytes", b.len);

    fc_mesh back;
    void *storage;
    CHECK_CODE(read_copy(b.data + FC_WIRE_HEADER_SIZE, b.len - FC_WIRE_HEADER_SIZE, &back, &storage, &err), FC_OK);
    CHECK(back.id == 7 && back.flags == FC_MESH_HIDE_NEAR && back.vertex_count == 3 && back.triangle_count == 1);
    CHECK(memcmp(back.vertices, triangle_vertices, sizeof triangle_vertices) == 0);
    CHECK(memcmp(back.indices, triangle_indices, sizeof triangle_indices) == 0);
    CHECK(back.normals == NULL && back.color[1] == 0.5f && back.opacity == 1.0f && back.transform[5] == 1.0f);
    free(storage);
    fc_buf_free(&b);
}

static void test_normals_round_trip(void)
{
    static const float normals[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    fc_mesh m = triangle_mesh();
    m.normals = normals;
    m.flags = 0;
    m.opacity = 0.25f;
    m.transform[3] = 5.0f;
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_mesh(&b, 1, &m, &err), FC_OK);
    CHECK(b.len == FC_WIRE_HEADER_SIZE + 80 + 36 + 12 + 36);
    CHECK(b.data[FC_WIRE_HEADER_SIZE + 4] == 1); /* flags: normals only */
    fc_mesh back;
    void *storage;
    CHECK_CODE(read_copy(b.data + FC_WIRE_HEADER_SIZE, b.len - FC_WIRE_HEADER_SIZE, &back, &storage, &err), FC_OK);
    CHECK(back.normals && memcmp(back.normals, normals, sizeof normals) == 0);
    CHECK(back.flags == 0 && back.opacity == 0.25f && back.transform[3] == 5.0f);
    free(storage);

    /* A removal: 80 bytes, V = T = 0, nothing allocated. */
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_mesh_removal(&b, 2, 7, &err), FC_OK);
    CHECK(b.len == FC_WIRE_HEADER_SIZE + 80);
    CHECK_CODE(read_copy(b.data + FC_WIRE_HEADER_SIZE, 80, &back, &storage, &err), FC_OK);
    CHECK(back.id == 7 && back.triangle_count == 0 && storage == NULL);
    fc_buf_free(&b);
}

/* The example's payload with one u32 (at byte `offset` of the payload) replaced. */
static fc_code read_patched(size_t offset, uint32_t value, size_t length_change, fc_error *err)
{
    uint8_t p[sizeof example_mesh + 8] = {0};
    size_t n = sizeof example_mesh - FC_WIRE_HEADER_SIZE;
    memcpy(p, example_mesh + FC_WIRE_HEADER_SIZE, n);
    if (offset != SIZE_MAX)
        memcpy(p + offset, &value, 4); /* the tests run on little-endian hosts (as the wire) */
    fc_mesh m;
    void *storage = NULL;
    fc_code code = read_copy(p, n + length_change, &m, &storage, err);
    free(storage);
    return code;
}

static uint32_t bits(float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    return u;
}

static void check_reject(size_t offset, uint32_t value, size_t length_change, fc_code expected, const char *phrase)
{
    fc_error err = {FC_OK, ""};
    fc_code code = read_patched(offset, value, length_change, &err);
    CHECK_MSG(code == expected && (!phrase || strstr(err.message, phrase)), "offset %zu: got %d '%s', want %d '%s'",
              offset, (int)code, err.message, (int)expected, phrase ? phrase : "");
}

static void test_rejections(void)
{
    const size_t flags = 4, vcount = 8, tcount = 12, color = 16, opacity = 28, transform = 32, vertices = 80,
                 indices = 116;
    /* 12.1 in order: length below the fixed part, unknown flags, limits, lengths, values. */
    fc_error err;
    fc_mesh m;
    void *storage;
    CHECK_CODE(fc_wire_read_mesh(example_mesh + FC_WIRE_HEADER_SIZE, 79, &m, &storage, &err), FC_ERR_MALFORMED);
    check_reject(flags, 4, 0, FC_ERR_MALFORMED, "flag");
    check_reject(vcount, FC_MESH_MAX_VERTICES + 1, 0, FC_ERR_LIMIT, "exceed");
    check_reject(tcount, 0xffffffffu, 0, FC_ERR_LIMIT, "exceed");
    check_reject(vcount, 4, 0, FC_ERR_MALFORMED, "do not match");
    check_reject(flags, 1, 0, FC_ERR_MALFORMED, "with normals");          /* normals announced, absent */
    check_reject(SIZE_MAX, 0, 4, FC_ERR_MALFORMED, "do not match");       /* 4 bytes too many */
    check_reject(color + 4, bits(1.5f), 0, FC_ERR_INVALID_VALUE, "color");
    check_reject(color, 0x7fc00000u, 0, FC_ERR_INVALID_VALUE, "color");
    check_reject(opacity, bits(-0.5f), 0, FC_ERR_INVALID_VALUE, "opacity");
    check_reject(transform + 44, 0x7f800000u, 0, FC_ERR_INVALID_VALUE, "transform");
    check_reject(vertices + 16, 0x7fc00000u, 0, FC_ERR_INVALID_VALUE, "vertex 1 ");
    check_reject(vertices + 32, 0xff800000u, 0, FC_ERR_INVALID_VALUE, "vertex 2 ");
    check_reject(indices + 8, 3, 0, FC_ERR_INVALID_VALUE, "triangle 0 refers to vertex 3");
    check_reject(indices, 0xffffffffu, 0, FC_ERR_INVALID_VALUE, "vertex 4294967295");

    /* V > 0 with T = 0 (lengths made to match: 3 vertices, no indices). */
    uint8_t p[80 + 36];
    memcpy(p, example_mesh + FC_WIRE_HEADER_SIZE, sizeof p);
    memset(p + tcount, 0, 4);
    CHECK_CODE(read_copy(p, sizeof p, &m, &storage, &err), FC_ERR_INVALID_VALUE);
    CHECK(strstr(err.message, "no triangles") != NULL);

    /* The writer refuses what the reader would, before writing anything. */
    fc_buf b;
    fc_buf_init(&b);
    static const uint32_t bad_indices[3] = {0, 1, 3};
    fc_mesh bad = triangle_mesh();
    bad.indices = bad_indices;
    CHECK_CODE(fc_wire_write_mesh(&b, 1, &bad, &err), FC_ERR_INVALID_VALUE);
    CHECK(b.len == 0 && strstr(err.message, "triangle 0") != NULL);
    bad = triangle_mesh();
    bad.flags = 8;
    CHECK_CODE(fc_wire_write_mesh(&b, 1, &bad, &err), FC_ERR_USAGE);
    bad = triangle_mesh();
    bad.triangle_count = FC_MESH_MAX_TRIANGLES + 1;
    CHECK_CODE(fc_wire_write_mesh(&b, 1, &bad, &err), FC_ERR_LIMIT);
    CHECK(b.len == 0);
    fc_buf_free(&b);
}

static void test_transforms(void)
{
    fc_mesh_transform e[2] = {{.id = 3}, {.id = 0x01020304}};
    fc_mesh_identity(e[0].transform);
    fc_mesh_identity(e[1].transform);
    e[1].transform[3] = 2.0f; /* x + 2 */
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_mesh_transforms(&b, 5, e, 2, &err), FC_OK);
    /* header: type 13, id 5, length 4 + 2 * 52 = 108 */
    const uint8_t head[] = {'F', 'C', 'S', 'T', 13, 0, 0, 0, 5, 0, 0, 0, 108, 0, 0, 0, 2, 0, 0, 0, 3, 0, 0, 0};
    CHECK(b.len == 16 + 108 && memcmp(b.data, head, sizeof head) == 0);
    const uint8_t second[] = {0x04, 0x03, 0x02, 0x01, 0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0, 0, 0, 0, 0, 0x00, 0x00, 0x00, 0x40};
    CHECK(memcmp(b.data + 16 + 4 + 52, second, sizeof second) == 0);

    fc_mesh_transform back[FC_MESH_MAX_COUNT];
    uint32_t count = 0;
    const uint8_t *p = b.data + 16;
    CHECK_CODE(fc_wire_read_mesh_transforms(p, 108, back, &count, &err), FC_OK);
    CHECK(count == 2 && back[1].id == 0x01020304 && back[1].transform[3] == 2.0f && back[0].transform[0] == 1.0f);

    CHECK_CODE(fc_wire_read_mesh_transforms(p, 3, back, &count, &err), FC_ERR_MALFORMED);
    CHECK_CODE(fc_wire_read_mesh_transforms(p, 107, back, &count, &err), FC_ERR_MALFORMED);
    uint8_t q[108];
    memcpy(q, p, sizeof q);
    q[0] = 65;
    CHECK_CODE(fc_wire_read_mesh_transforms(q, 108, back, &count, &err), FC_ERR_LIMIT);
    memcpy(q, p, sizeof q);
    memcpy(q + 4 + 52, q + 4, 4); /* the same id twice */
    CHECK_CODE(fc_wire_read_mesh_transforms(q, 108, back, &count, &err), FC_ERR_INVALID_VALUE);
    CHECK(strstr(err.message, "mesh 3 appears in entries 0 and 1") != NULL);
    memcpy(q, p, sizeof q);
    uint32_t nan = 0x7fc00000u;
    memcpy(q + 4 + 52 + 4 + 20, &nan, 4);
    CHECK_CODE(fc_wire_read_mesh_transforms(q, 108, back, &count, &err), FC_ERR_INVALID_VALUE);
    CHECK(strstr(err.message, "entry 1") != NULL);
    /* An empty update is valid. */
    const uint8_t empty[4] = {0};
    CHECK_CODE(fc_wire_read_mesh_transforms(empty, 4, back, &count, &err), FC_OK);
    CHECK(count == 0);
    fc_buf_free(&b);
}

/* Every proper prefix of a valid MESH or MESH_TRANSFORM payload is MALFORMED. */
static void test_every_truncation(void)
{
    const uint8_t *mesh = example_mesh + FC_WIRE_HEADER_SIZE;
    size_t mesh_n = sizeof example_mesh - FC_WIRE_HEADER_SIZE;
    for (size_t n = 0; n < mesh_n; n++) {
        fc_error err;
        fc_mesh m;
        void *storage = NULL;
        fc_code code = read_copy(mesh, n, &m, &storage, &err);
        CHECK_MSG(code == FC_ERR_MALFORMED && storage == NULL, "MESH cut to %zu bytes: %d", n, (int)code);
    }
    fc_mesh_transform e = {.id = 1};
    fc_mesh_identity(e.transform);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_mesh_transforms(&b, 1, &e, 1, &err), FC_OK);
    for (size_t n = 0; n + FC_WIRE_HEADER_SIZE < b.len; n++) {
        uint8_t *copy = malloc(n ? n : 1);
        memcpy(copy, b.data + FC_WIRE_HEADER_SIZE, n);
        fc_mesh_transform back[FC_MESH_MAX_COUNT];
        uint32_t count;
        CHECK_MSG(fc_wire_read_mesh_transforms(copy, n, back, &count, &err) == FC_ERR_MALFORMED,
                  "MESH_TRANSFORM cut to %zu bytes", n);
        free(copy);
    }
    fc_buf_free(&b);
}

int main(void)
{
    test_every_truncation();
    test_example_bytes();
    test_normals_round_trip();
    test_rejections();
    test_transforms();
    return test_result();
}
