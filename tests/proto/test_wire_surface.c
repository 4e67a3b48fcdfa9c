/* test_wire_surface.c — SURFACE and SURFACE_PART (PROTOCOL.md section 13): the
 * request's bytes, meshes round-tripping through one part and through several,
 * and each check of 13.3 refusing a hostile reply with its code. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "test_util.h"
#include "wire.h"
#include "wire_io.h"
#include "wire_surface.h"

/* A deterministic mesh of `triangles` triangles over triangles + 2 vertices (a strip), with `attributes`. */
static fc_surface_mesh strip_mesh(uint32_t triangles, uint32_t attributes)
{
    fc_surface_mesh m = {.vertex_count = triangles + 2, .triangle_count = triangles, .attributes = attributes};
    uint32_t v = m.vertex_count;
    m.positions = malloc(12ull * v);
    m.normals = malloc(12ull * v);
    m.indices = malloc(12ull * triangles);
    m.speed = attributes & FC_SURFACE_SPEED ? malloc(4ull * v) : NULL;
    m.density = attributes & FC_SURFACE_DENSITY ? malloc(4ull * v) : NULL;
    m.velocity = attributes & FC_SURFACE_VELOCITY ? malloc(12ull * v) : NULL;
    m.id = attributes & FC_SURFACE_ID ? malloc(4ull * v) : NULL;
    for (uint32_t i = 0; i < v; i++) {
        float x = (float)(i / 2), y = (float)(i % 2);
        float p[3] = {x, y, 0.25f * x}, n[3] = {0, 0, 1};
        memcpy(m.positions + 3 * i, p, sizeof p);
        memcpy(m.normals + 3 * i, n, sizeof n);
        if (m.speed)
            m.speed[i] = 0.5f * x;
        if (m.density)
            m.density[i] = 1000.0f + y;
        if (m.velocity)
            for (int k = 0; k < 3; k++)
                m.velocity[3 * i + k] = x + (float)k;
        if (m.id)
            m.id[i] = 7u * i + 1u;
    }
    for (uint32_t t = 0; t < triangles; t++) {
        uint32_t tri[3] = {t, t % 2 ? t + 2 : t + 1, t % 2 ? t + 1 : t + 2};
        memcpy(m.indices + 3 * t, tri, sizeof tri);
    }
    return m;
}

static bool same_floats(const float *a, const float *b, uint64_t n)
{
    return (a == NULL) == (b == NULL) && (!a || memcmp(a, b, 4 * n) == 0);
}

static void check_same_mesh(const fc_surface_mesh *a, const fc_surface_mesh *b)
{
    CHECK(a->vertex_count == b->vertex_count);
    CHECK(a->triangle_count == b->triangle_count);
    CHECK(a->attributes == b->attributes);
    uint64_t v = a->vertex_count;
    CHECK(same_floats(a->positions, b->positions, 3 * v));
    CHECK(same_floats(a->normals, b->normals, 3 * v));
    CHECK(memcmp(a->indices, b->indices, 12ull * a->triangle_count) == 0);
    CHECK(same_floats(a->speed, b->speed, v));
    CHECK(same_floats(a->density, b->density, v));
    CHECK(same_floats(a->velocity, b->velocity, 3 * v));
    CHECK((a->id == NULL) == (b->id == NULL) && (!a->id || memcmp(a->id, b->id, 4 * v) == 0));
}

/* Feeds every part of `mesh`'s reply to a new assembly; returns the first failure. */
static fc_code send_through(const fc_surface_mesh *mesh, fc_surface_mesh *received, float *extract_ms,
                            uint32_t *parts_sent, fc_error *err)
{
    uint32_t parts = fc_surface_part_count(
        fc_surface_body_size(mesh->vertex_count, mesh->triangle_count, mesh->attributes));
    fc_surface_assembly a;
    fc_surface_assembly_init(&a, 0);
    fc_buf b;
    fc_buf_init(&b);
    fc_code code = FC_OK;
    bool complete = false;
    for (uint32_t i = 0; i < parts && code == FC_OK; i++) {
        fc_buf_reset(&b);
        code = fc_wire_write_surface_part(&b, 9, mesh, 12.5f, i, err);
        if (code == FC_OK) {
            fc_msg_header h;
            CHECK_CODE(fc_wire_decode_header(b.data, UINT32_MAX, &h, err), FC_OK);
            CHECK(h.type == FC_MSG_SURFACE_PART && h.request_id == 9);
            CHECK(h.length == b.len - FC_WIRE_HEADER_SIZE && h.length <= FC_SURFACE_PART_FIXED_SIZE + FC_SURFACE_PART_DATA_MAX);
            code = fc_surface_assembly_add(&a, b.data + FC_WIRE_HEADER_SIZE, h.length, &complete, err);
            CHECK(complete == (code == FC_OK && i + 1 == parts));
        }
    }
    if (code == FC_OK)
        code = fc_surface_assembly_finish(&a, received, extract_ms, err);
    *parts_sent = parts;
    fc_surface_assembly_free(&a);
    fc_buf_free(&b);
    return code;
}

static void test_request(void)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_surface_request(&b, 3, FC_SURFACE_SPEED | FC_SURFACE_ID, &err), FC_OK);
    static const uint8_t expected[] = {'F', 'C', 'S', 'T', 25, 0, 0, 0, 3, 0, 0, 0, 4, 0, 0, 0, 9, 0, 0, 0};
    CHECK(b.len == sizeof expected && memcmp(b.data, expected, sizeof expected) == 0);
    uint32_t bits = 0;
    CHECK_CODE(fc_wire_read_surface_request(b.data + 16, 4, &bits, &err), FC_OK);
    CHECK(bits == (FC_SURFACE_SPEED | FC_SURFACE_ID));
    CHECK_CODE(fc_wire_read_surface_request(b.data + 16, 3, &bits, &err), FC_ERR_MALFORMED);
    static const uint8_t unknown_bit[4] = {16, 0, 0, 0};
    CHECK_CODE(fc_wire_read_surface_request(unknown_bit, 4, &bits, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(fc_wire_write_surface_request(&b, 3, 32, &err), FC_ERR_INVALID_VALUE);
    CHECK(strcmp(fc_msg_name(FC_MSG_SURFACE), "SURFACE") == 0);
    CHECK(strcmp(fc_msg_name(FC_MSG_SURFACE_PART), "SURFACE_PART") == 0);
    fc_buf_free(&b);
}

static void test_round_trip(uint32_t triangles, uint32_t attributes, uint32_t expected_parts)
{
    fc_surface_mesh sent = strip_mesh(triangles, attributes), received;
    fc_error err = {FC_OK, ""};
    float ms = 0;
    uint32_t parts = 0;
    CHECK_CODE(send_through(&sent, &received, &ms, &parts, &err), FC_OK);
    CHECK_MSG(parts == expected_parts, "%u parts, expected %u", (unsigned)parts, (unsigned)expected_parts);
    CHECK(ms == 12.5f);
    check_same_mesh(&sent, &received);
    fc_surface_mesh_free(&sent);
    fc_surface_mesh_free(&received);
}

static void test_empty_surface(void)
{
    fc_surface_mesh none = {0}, received;
    fc_error err;
    float ms = 0;
    uint32_t parts = 0;
    CHECK_CODE(send_through(&none, &received, &ms, &parts, &err), FC_OK);
    CHECK(parts == 1 && received.vertex_count == 0 && received.positions == NULL);
}

/* One part's fixed fields, for hand-made hostile parts. */
static void put_fields(fc_buf *b, uint32_t index, uint32_t count, uint32_t v, uint32_t t, uint32_t a, uint64_t offset,
                       uint32_t size)
{
    fc_buf_reset(b);
    wire_put_u32(b, index);
    wire_put_u32(b, count);
    wire_put_u32(b, v);
    wire_put_u32(b, t);
    wire_put_u32(b, a);
    wire_put_f32(b, -1.0f);
    wire_put_u64(b, offset);
    wire_put_u32(b, size);
}

static fc_code add_one(const fc_buf *b, fc_surface_assembly *a, fc_error *err)
{
    bool complete = false;
    return fc_surface_assembly_add(a, b->data, b->len, &complete, err);
}

static void test_hostile_first_parts(void)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_surface_assembly a;
    struct { uint32_t count, v, t, attributes; fc_code code; } cases[] = {
        {1, UINT32_MAX, 1, 0, FC_ERR_LIMIT},                     /* huge vertex count */
        {1, 3, UINT32_MAX, 0, FC_ERR_LIMIT},                     /* huge triangle count */
        {1, 3, 0, 0, FC_ERR_INVALID_VALUE},                      /* vertices without triangles */
        {1, 3, 1, 16, FC_ERR_INVALID_VALUE},                     /* unknown attribute */
        {5, 3, 1, 0, FC_ERR_MALFORMED},                          /* K not what B gives */
        {0, 3, 1, 0, FC_ERR_MALFORMED},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        fc_surface_assembly_init(&a, 0);
        put_fields(&b, 0, cases[i].count, cases[i].v, cases[i].t, cases[i].attributes, 0, 0);
        CHECK_CODE(add_one(&b, &a, &err), cases[i].code);
        CHECK_MSG(a.body == NULL, "case %zu allocated before any data arrived", i);
        fc_surface_assembly_free(&a);
    }
    /* The receiver's own bound: a reply of 3 vertices refused by a receiver taking 64 bytes. */
    fc_surface_assembly_init(&a, 64);
    put_fields(&b, 0, 1, 3, 1, 0, 0, 84);
    CHECK_CODE(add_one(&b, &a, &err), FC_ERR_LIMIT);
    fc_surface_assembly_free(&a);
    /* Truncated fixed fields, and data not matching `size`. */
    fc_surface_assembly_init(&a, 0);
    CHECK_CODE(fc_surface_assembly_add(&a, b.data, 35, &(bool){false}, &err), FC_ERR_MALFORMED);
    fc_surface_assembly_free(&a);
    fc_surface_assembly_init(&a, 0);
    put_fields(&b, 0, 1, 3, 1, 0, 0, 84);
    CHECK_CODE(add_one(&b, &a, &err), FC_ERR_MALFORMED);   /* 84 announced, none follow */
    fc_surface_assembly_free(&a);
    fc_buf_free(&b);
}

/* A two-part reply with part 1 altered by `alter`; the code the assembly answers part 1 with. */
static fc_code second_part_altered(void (*alter)(uint8_t *fields))
{
    fc_surface_mesh mesh = strip_mesh(400000, FC_SURFACE_ATTRIBUTES_ALL);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_surface_assembly a;
    fc_surface_assembly_init(&a, 0);
    bool complete = false;
    CHECK_CODE(fc_wire_write_surface_part(&b, 1, &mesh, 1.0f, 0, &err), FC_OK);
    CHECK_CODE(fc_surface_assembly_add(&a, b.data + 16, b.len - 16, &complete, &err), FC_OK);
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_surface_part(&b, 1, &mesh, 1.0f, 1, &err), FC_OK);
    alter(b.data + 16);
    fc_code code = fc_surface_assembly_add(&a, b.data + 16, b.len - 16, &complete, &err);
    CHECK(complete == (code == FC_OK));   /* part 1 is the last */
    /* A failed assembly takes nothing more, not even the true part. */
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_surface_part(&b, 1, &mesh, 1.0f, 1, &err), FC_OK);
    if (code != FC_OK)
        CHECK_CODE(fc_surface_assembly_add(&a, b.data + 16, b.len - 16, &complete, &err), FC_ERR_MALFORMED);
    fc_surface_assembly_free(&a);
    fc_surface_mesh_free(&mesh);
    fc_buf_free(&b);
    return code;
}

static void unchanged(uint8_t *f) { (void)f; }
static void index_repeated(uint8_t *f) { wire_store_le(f, 0, 4); }
static void count_changed(uint8_t *f) { wire_store_le(f + 4, 3, 4); }
static void vertices_changed(uint8_t *f) { wire_store_le(f + 8, 400001, 4); }
static void attributes_changed(uint8_t *f) { wire_store_le(f + 16, 1, 4); }
static void offset_moved(uint8_t *f) { wire_store_le(f + 24, 4, 8); }
static void size_changed(uint8_t *f) { wire_store_le(f + 32, 4, 4); }

static void test_bad_sequences(void)
{
    CHECK_CODE(second_part_altered(unchanged), FC_OK);
    CHECK_CODE(second_part_altered(index_repeated), FC_ERR_MALFORMED);
    CHECK_CODE(second_part_altered(count_changed), FC_ERR_INCONSISTENT);
    CHECK_CODE(second_part_altered(vertices_changed), FC_ERR_INCONSISTENT);
    CHECK_CODE(second_part_altered(attributes_changed), FC_ERR_INCONSISTENT);
    CHECK_CODE(second_part_altered(offset_moved), FC_ERR_MALFORMED);
    CHECK_CODE(second_part_altered(size_changed), FC_ERR_MALFORMED);
}

/* A whole reply whose body breaks 13.3 step 5; the writer refuses such a mesh, so the bytes are altered after it. */
static fc_code whole_reply_altered(size_t body_offset, uint32_t value)
{
    fc_surface_mesh mesh = strip_mesh(2, 0);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_surface_part(&b, 1, &mesh, 1.0f, 0, &err), FC_OK);
    wire_store_le(b.data + 16 + FC_SURFACE_PART_FIXED_SIZE + body_offset, value, 4);
    fc_surface_assembly a;
    fc_surface_assembly_init(&a, 0);
    fc_surface_mesh out;
    bool complete = false;
    CHECK_CODE(fc_surface_assembly_add(&a, b.data + 16, b.len - 16, &complete, &err), FC_OK);
    CHECK(complete);
    fc_code code = fc_surface_assembly_finish(&a, &out, NULL, &err);
    if (code == FC_OK)
        fc_surface_mesh_free(&out);
    else
        CHECK(out.positions == NULL);
    fc_surface_assembly_free(&a);
    fc_surface_mesh_free(&mesh);
    fc_buf_free(&b);
    return code;
}

static void test_bad_bodies(void)
{
    CHECK_CODE(whole_reply_altered(4, 0x7fc00000u), FC_ERR_INVALID_VALUE);          /* NaN position */
    CHECK_CODE(whole_reply_altered(12 * 4 + 8, 0x7f800000u), FC_ERR_INVALID_VALUE); /* Inf normal */
    CHECK_CODE(whole_reply_altered(24 * 4 + 4, 4), FC_ERR_INVALID_VALUE);           /* index 4 of 4 vertices */
    CHECK_CODE(whole_reply_altered(24 * 4 + 4, 3), FC_OK);
    fc_error err;
    fc_surface_mesh nan_mesh = strip_mesh(2, 0);
    nan_mesh.positions[5] = NAN;
    fc_buf b;
    fc_buf_init(&b);
    CHECK_CODE(fc_wire_write_surface_part(&b, 1, &nan_mesh, 1.0f, 0, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(fc_wire_write_surface_part(&b, 1, &nan_mesh, 1.0f, 1, &err), FC_ERR_INVALID_VALUE);
    nan_mesh.positions[5] = 0;
    CHECK_CODE(fc_wire_write_surface_part(&b, 1, &nan_mesh, 1.0f, 1, &err), FC_ERR_USAGE);
    fc_surface_mesh_free(&nan_mesh);
    fc_buf_free(&b);
}

int main(void)
{
    test_request();
    test_round_trip(1, 0, 1);
    test_round_trip(33, FC_SURFACE_ATTRIBUTES_ALL, 1);
    test_round_trip(17, FC_SURFACE_VELOCITY | FC_SURFACE_ID, 1);
    /* 400002 vertices * 56 bytes + 400000 triangles * 12 bytes: two parts. */
    test_round_trip(400000, FC_SURFACE_ATTRIBUTES_ALL, 2);
    test_empty_surface();
    test_hostile_first_parts();
    test_bad_sequences();
    test_bad_bodies();
    return test_result();
}
