/* test_hardening_mesh.c — hostile MESH and MESH_TRANSFORM messages against the
 * real fluidcastd (PROTOCOL.md section 12): indices past the vertices, NaN and
 * infinite vertices and normals, counts beyond the limits, lengths that do
 * not add up, values outside their domains, a 65th mesh, a mesh beyond the
 * connection's memory limit, moves of meshes never sent, on a plain and on a
 * producer connection. Each gets its exact ERROR, the connection stays open
 * and renders correctly after, and the witness is served throughout.
 *
 * The valid meshes sent lie far below the test cube (z = -100), so the cube's
 * depth image stays what the harness expects whatever draws them. */
#include <stdbool.h>
#include <string.h>
#include <unistd.h>

#include "hardening_harness.h"
#include "test_util.h"
#include "wire_mesh.h"

/* 2 MB: the witness's and the cases' cube frames fit, a 100000-vertex mesh with normals does not. */
static const char *const daemon_args[] = {"--max-session-memory", "2000000", NULL};

#define QUIET_NAN 0x7fc00000u
#define PLUS_INF 0x7f800000u
#define ONE 0x3f800000u

/* A raw MESH, written field by field: one triangle fan over `vertices`
 * vertices on a circle at z = -100, with hooks to break any part of it. */
typedef struct mesh_row {
    uint32_t id, flags, vertex_count, triangle_count;
    uint32_t color_g, opacity, transform_z;     /* bits */
    uint32_t poison_vertex_word, poison;        /* vertex word index and its bits; poison 0 = none */
    uint32_t poison_index, bad_index;           /* index word and its value; bad_index 0 = none */
    int length_change;                          /* bytes added to (or cut from) the arrays */
    bool omit_normals;                          /* announce normals, send none */
    uint32_t request_id;
} mesh_row;

static mesh_row good_row(uint32_t id, uint32_t vertices)
{
    return (mesh_row){.id = id, .vertex_count = vertices, .triangle_count = vertices - 2, .color_g = ONE,
                      .opacity = ONE, .transform_z = 0xc2c80000u /* -100 */, .request_id = HX_BAD_ID};
}

static uint32_t bits(float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    return u;
}

static void write_mesh(fc_buf *out, const mesh_row *r, uint32_t array_vertices, uint32_t array_triangles)
{
    size_t at = hx_begin(out, FC_MSG_MESH, r->request_id);
    hx_u32(out, r->id);
    hx_u32(out, r->flags);
    hx_u32(out, r->vertex_count);
    hx_u32(out, r->triangle_count);
    hx_u32(out, ONE);
    hx_u32(out, r->color_g);
    hx_u32(out, ONE);
    hx_u32(out, r->opacity);
    const uint32_t transform[12] = {ONE, 0, 0, 0, 0, ONE, 0, 0, 0, 0, ONE, r->transform_z};
    for (int i = 0; i < 12; i++)
        hx_u32(out, transform[i]);
    for (uint32_t v = 0; v < array_vertices; v++)
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t word = 3 * v + k;
            float value = k == 2 ? 0.0f : (k == 0 ? 1.0f : 0.5f) * (float)(v % 7) / 7.0f;
            hx_u32(out, r->poison && word == r->poison_vertex_word ? r->poison : bits(value));
        }
    for (uint32_t t = 0; t < array_triangles; t++)
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t word = 3 * t + k, index = k == 0 ? 0 : t + k;
            hx_u32(out, r->bad_index && word == r->poison_index ? r->bad_index : index);
        }
    if ((r->flags & FC_MESH_WIRE_NORMALS) && !r->omit_normals)
        for (uint32_t v = 0; v < 3 * array_vertices; v++)
            hx_u32(out, r->poison && 3 * array_vertices + v == r->poison_vertex_word ? r->poison
                                                                                      : (v % 3 == 2 ? ONE : 0));
    for (int i = 0; i < r->length_change; i++)
        hx_bytes(out, "\0", 1);
    out->len -= r->length_change < 0 ? (size_t)-r->length_change : 0;
    hx_end(out, at);
}

static void send_row(fc_buf *out, const mesh_row *r)
{
    write_mesh(out, r, r->vertex_count, r->triangle_count);
}

static void index_equals_v(fc_buf *out)
{
    mesh_row r = good_row(1, 5);
    r.poison_index = 3 * 2 + 2; /* triangle 2's third index */
    r.bad_index = 5;
    send_row(out, &r);
}

static void index_huge(fc_buf *out)
{
    mesh_row r = good_row(1, 4);
    r.poison_index = 1;
    r.bad_index = 0xffffffffu;
    send_row(out, &r);
}

static void nan_vertex(fc_buf *out)
{
    mesh_row r = good_row(1, 6);
    r.poison_vertex_word = 3 * 4 + 1;
    r.poison = QUIET_NAN;
    send_row(out, &r);
}

static void inf_normal(fc_buf *out)
{
    mesh_row r = good_row(1, 6);
    r.flags = FC_MESH_WIRE_NORMALS;
    r.poison_vertex_word = 3 * 6 + 5;
    r.poison = PLUS_INF;
    send_row(out, &r);
}

static void vertices_over_limit(fc_buf *out)
{
    mesh_row r = good_row(1, 3);
    r.vertex_count = FC_MESH_MAX_VERTICES + 1;
    write_mesh(out, &r, 3, 1); /* refused on the counts, before the (short) arrays are looked at */
}

static void triangles_over_limit(fc_buf *out)
{
    mesh_row r = good_row(1, 3);
    r.triangle_count = 0xffffffffu;
    write_mesh(out, &r, 3, 1);
}

static void arrays_short(fc_buf *out)
{
    mesh_row r = good_row(1, 8);
    r.length_change = -4;
    send_row(out, &r);
}

static void arrays_long(fc_buf *out)
{
    mesh_row r = good_row(1, 8);
    r.length_change = 12;
    send_row(out, &r);
}

static void normals_missing(fc_buf *out)
{
    mesh_row r = good_row(1, 8);
    r.flags = FC_MESH_WIRE_NORMALS;
    r.omit_normals = true;
    send_row(out, &r);
}

static void fixed_part_short(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_MESH, HX_BAD_ID);
    for (int i = 0; i < 19; i++)
        hx_u32(out, 0);
    hx_end(out, at);
}

static void unknown_flag(fc_buf *out)
{
    mesh_row r = good_row(1, 4);
    r.flags = 4;
    send_row(out, &r);
}

static void vertices_without_triangles(fc_buf *out)
{
    mesh_row r = good_row(1, 4);
    r.triangle_count = 0;
    send_row(out, &r);
}

static void color_out_of_range(fc_buf *out)
{
    mesh_row r = good_row(1, 4);
    r.color_g = bits(1.25f);
    send_row(out, &r);
}

static void opacity_nan(fc_buf *out)
{
    mesh_row r = good_row(1, 4);
    r.opacity = QUIET_NAN;
    send_row(out, &r);
}

static void transform_inf(fc_buf *out)
{
    mesh_row r = good_row(1, 4);
    r.transform_z = PLUS_INF;
    send_row(out, &r);
}

static void valid_mesh(fc_buf *out)
{
    mesh_row r = good_row(1, 12);
    r.flags = FC_MESH_WIRE_NORMALS | FC_MESH_HIDE_NEAR;
    send_row(out, &r);
}

static void valid_mesh_replaced_and_removed(fc_buf *out)
{
    mesh_row r = good_row(4, 12);
    r.request_id = HX_PRELUDE_ID;
    send_row(out, &r);
    r = good_row(4, 30);
    r.request_id = HX_PRELUDE_ID + 1;
    send_row(out, &r);
    r = good_row(4, 2);
    r.vertex_count = r.triangle_count = 0;
    send_row(out, &r);
}

static void sixty_fifth_mesh(fc_buf *out)
{
    for (uint32_t id = 0; id < FC_MESH_MAX_COUNT; id++) {
        mesh_row r = good_row(100 + id, 3);
        r.request_id = HX_PRELUDE_ID;
        send_row(out, &r);
    }
    mesh_row replace = good_row(100, 4); /* replacing one of the 64 is fine */
    replace.request_id = HX_PRELUDE_ID;
    send_row(out, &replace);
    mesh_row r = good_row(99, 3);
    send_row(out, &r);
}

static void beyond_memory(fc_buf *out)
{
    mesh_row r = good_row(1, 100000); /* 2.4 MB of vertices and normals, 1.2 MB of indices */
    r.flags = FC_MESH_WIRE_NORMALS;
    send_row(out, &r);
}

/* MESH_TRANSFORM with `count` entries for ids first, first+1, ...; a poison
 * bit pattern in entry `poisoned`'s translation when poison != 0. */
static void write_transforms(fc_buf *out, uint32_t count, uint32_t first, uint32_t poisoned, uint32_t poison,
                             int length_change)
{
    size_t at = hx_begin(out, FC_MSG_MESH_TRANSFORM, HX_BAD_ID);
    hx_u32(out, count);
    for (uint32_t i = 0; i < count; i++) {
        hx_u32(out, first + i);
        const uint32_t m[12] = {ONE, 0, 0, 0, 0, ONE, 0, 0, 0, 0, ONE, poison && i == poisoned ? poison : 0xc2c80000u};
        for (int k = 0; k < 12; k++)
            hx_u32(out, m[k]);
    }
    if (length_change < 0)
        out->len -= (size_t)-length_change;
    hx_end(out, at);
}

static void two_meshes(fc_buf *out)
{
    for (uint32_t id = 1; id <= 2; id++) {
        mesh_row r = good_row(id, 4);
        r.request_id = HX_PRELUDE_ID;
        send_row(out, &r);
    }
}

static void move_unknown(fc_buf *out)
{
    two_meshes(out);
    write_transforms(out, 3, 1, 0, 0, 0); /* ids 1, 2 and 3: 3 was never sent */
}

static void move_known(fc_buf *out)
{
    two_meshes(out);
    write_transforms(out, 2, 1, 0, 0, 0);
}

static void move_nan(fc_buf *out)
{
    two_meshes(out);
    write_transforms(out, 2, 1, 1, QUIET_NAN, 0);
}

static void move_cut(fc_buf *out)
{
    two_meshes(out);
    write_transforms(out, 2, 1, 0, 0, -5);
}

static void move_too_many(fc_buf *out)
{
    write_transforms(out, FC_MESH_MAX_COUNT + 1, 1, 0, 0, 0);
}

static void move_duplicate(fc_buf *out)
{
    two_meshes(out);
    size_t at = hx_begin(out, FC_MSG_MESH_TRANSFORM, HX_BAD_ID);
    hx_u32(out, 2);
    for (int i = 0; i < 2; i++) {
        hx_u32(out, 2);
        const uint32_t m[12] = {ONE, 0, 0, 0, 0, ONE, 0, 0, 0, 0, ONE, 0};
        for (int k = 0; k < 12; k++)
            hx_u32(out, m[k]);
    }
    hx_end(out, at);
}

static const hx_case cases[] = {
    {"MESH: an index equal to V", HX_GREETED, index_equals_v, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH: index 2^32-1", HX_GREETED, index_huge, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH: NaN vertex", HX_GREETED, nan_vertex, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH: +Inf normal", HX_GREETED, inf_normal, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH: V beyond 2^24", HX_GREETED, vertices_over_limit, FC_ERR_LIMIT, HX_STAYS_OPEN, false},
    {"MESH: T = 2^32-1", HX_GREETED, triangles_over_limit, FC_ERR_LIMIT, HX_STAYS_OPEN, false},
    {"MESH: arrays 4 bytes short", HX_GREETED, arrays_short, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"MESH: 12 bytes after the arrays", HX_GREETED, arrays_long, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"MESH: normals announced, absent", HX_GREETED, normals_missing, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"MESH: 76 bytes", HX_GREETED, fixed_part_short, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"MESH: unknown flag bit", HX_GREETED, unknown_flag, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"MESH: vertices, no triangles", HX_GREETED, vertices_without_triangles, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN,
     false},
    {"MESH: colour 1.25", HX_GREETED, color_out_of_range, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH: NaN opacity", HX_GREETED, opacity_nan, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH: infinite transform", HX_GREETED, transform_inf, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH: a valid one", HX_GREETED, valid_mesh, FC_OK, HX_STAYS_OPEN, false},
    {"MESH: replaced, then removed", HX_GREETED, valid_mesh_replaced_and_removed, FC_OK, HX_STAYS_OPEN, false},
    {"MESH: a 65th mesh", HX_GREETED, sixty_fifth_mesh, FC_ERR_LIMIT, HX_STAYS_OPEN, false},
    {"MESH: beyond max_session_memory", HX_GREETED, beyond_memory, FC_ERR_LIMIT, HX_STAYS_OPEN, false},
    {"MESH before HELLO", HX_RAW, valid_mesh, FC_ERR_BAD_STATE, HX_CLOSES, false},
    {"MESH on a producer: NaN vertex", HX_PUBLISHING, nan_vertex, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH_TRANSFORM: a mesh never sent", HX_GREETED, move_unknown, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
    {"MESH_TRANSFORM: two meshes moved", HX_GREETED, move_known, FC_OK, HX_STAYS_OPEN, false},
    {"MESH_TRANSFORM: NaN translation", HX_GREETED, move_nan, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH_TRANSFORM: cut short", HX_GREETED, move_cut, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"MESH_TRANSFORM: 65 entries", HX_GREETED, move_too_many, FC_ERR_LIMIT, HX_STAYS_OPEN, false},
    {"MESH_TRANSFORM: one id twice", HX_GREETED, move_duplicate, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"MESH_TRANSFORM on a producer: never sent", HX_PUBLISHING, move_unknown, FC_ERR_BAD_STATE, HX_STAYS_OPEN,
     false},
};

/* The reason names what was wrong: the triangle, the vertex, the limit. */
static void test_reasons(hx_env *env)
{
    struct {
        void (*build)(fc_buf *);
        fc_code code;
        const char *phrase;
    } rows[] = {
        {index_equals_v, FC_ERR_INVALID_VALUE, "triangle 2 refers to vertex 5, but the mesh has 5 vertices"},
        {nan_vertex, FC_ERR_INVALID_VALUE, "vertex 4 is"},
        {inf_normal, FC_ERR_INVALID_VALUE, "normal 1 is"},
        {beyond_memory, FC_ERR_LIMIT, "max_session_memory"},
        {sixty_fifth_mesh, FC_ERR_LIMIT, "64 meshes"},
        {move_unknown, FC_ERR_BAD_STATE, "no mesh 3"},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        int fd = hx_connect_greeted(env, 0);
        fc_buf out;
        fc_buf_init(&out);
        rows[i].build(&out);
        hx_send_buf(fd, &out);
        hx_expect_error_mentioning(fd, HX_BAD_ID, rows[i].code, rows[i].phrase);
        hx_expect_renders(fd, 700);
        fc_buf_free(&out);
        close(fd);
    }
}

int main(void)
{
    hx_env env;
    if (!hx_env_start(&env, daemon_args))
        return hx_exit_status(test_result());
    hx_run_cases(&env, cases, sizeof cases / sizeof cases[0]);
    test_reasons(&env);
    hx_env_stop(&env);
    return hx_exit_status(test_result());
}
