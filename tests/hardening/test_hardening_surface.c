/* test_hardening_surface.c — hostile SURFACE requests against the real
 * fluidcastd (PROTOCOL.md section 13): payloads of the wrong length, unknown
 * attribute bits, a request before any frame, a SURFACE_PART sent by a client,
 * a grid past the server's budget. Each gets its exact ERROR, the connection
 * stays open and renders correctly after, and the witness is served
 * throughout; a good request on the same kind of connection is answered by
 * its parts, in order, with the request's id. */
#include <stdbool.h>
#include <string.h>
#include <unistd.h>

#include "fc_settings.h"
#include "hardening_harness.h"
#include "test_util.h"
#include "wire_surface.h"

static void surface_short(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SURFACE, HX_BAD_ID);
    hx_u16(out, 0);
    hx_bytes(out, "\0", 1);
    hx_end(out, at);
}

static void surface_long(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SURFACE, HX_BAD_ID);
    hx_u32(out, 0);
    hx_u32(out, 0);
    hx_end(out, at);
}

static void surface_unknown_bit(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SURFACE, HX_BAD_ID);
    hx_u32(out, 1u << 4);
    hx_end(out, at);
}

static void surface_before_frame(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SURFACE, HX_BAD_ID);
    hx_u32(out, FC_SURFACE_ATTRIBUTES_ALL);
    hx_end(out, at);
}

/* A part of a reply, as a server would send it, from a client. */
static void part_from_client(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SURFACE_PART, HX_BAD_ID);
    hx_u32(out, 0);           /* index */
    hx_u32(out, 1);           /* count */
    hx_u32(out, 0);           /* V */
    hx_u32(out, 0);           /* T */
    hx_u32(out, 0);           /* attributes */
    hx_f32(out, -1.0f);       /* extract_ms */
    hx_u64(out, 0);           /* offset */
    hx_u32(out, 0);           /* size */
    hx_end(out, at);
}

/* SETTINGS of one float setting, written field by field (PROTOCOL.md 7.5). */
static void settings_float(fc_buf *out, uint32_t request_id, const char *name, float value)
{
    size_t at = hx_begin(out, FC_MSG_SETTINGS, request_id);
    hx_u32(out, 1);
    hx_u32(out, fc_setting_by_name(name)->key | 1u << 16);
    hx_f32(out, value);
    hx_end(out, at);
}

/* The cube rendered (its frame stays the connection's), then a radius so small that the grid of its
 * cells over the cube passes the server's budget: LIMIT. The settings go back for the runner's render. */
static void grid_past_budget(fc_buf *out)
{
    hx_write_render_sequence(out, HX_PRELUDE_ID);
    settings_float(out, HX_PRELUDE_ID + 3, "radius", 1e-5f);
    surface_before_frame(out);
}

static const hx_case cases[] = {
    {"SURFACE: 3 bytes", HX_GREETED, surface_short, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"SURFACE: 8 bytes", HX_GREETED, surface_long, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"SURFACE: attribute bit 4", HX_GREETED, surface_unknown_bit, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"SURFACE before any FRAME", HX_GREETED, surface_before_frame, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
    {"SURFACE_PART from a client", HX_GREETED, part_from_client, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
};

/* The grid case reads the prelude's IMAGE before the ERROR, and puts the radius back after. */
static void test_grid_past_budget(hx_env *env)
{
    int fd = hx_connect_greeted(env, 0);
    if (fd < 0)
        return;
    fc_buf out;
    fc_buf_init(&out);
    grid_past_budget(&out);
    hx_send_buf(fd, &out);
    hx_expect_cube_image(fd, HX_PRELUDE_ID + 2);
    hx_expect_error_mentioning(fd, HX_BAD_ID, FC_ERR_LIMIT, NULL);
    settings_float(&out, HX_PRELUDE_ID + 4, "radius", 0.0f);
    hx_send_buf(fd, &out);
    hx_expect_renders(fd, HX_PRELUDE_ID + 10);
    hx_expect_witness_served(env);
    fc_buf_free(&out);
    close(fd);
}

/* A good request: its one part answers it, then the connection renders on. */
static void test_good_request(hx_env *env)
{
    int fd = hx_connect_greeted(env, 0);
    if (fd < 0)
        return;
    fc_buf out;
    fc_buf_init(&out);
    hx_write_render_sequence(&out, HX_PRELUDE_ID);
    size_t at = hx_begin(&out, FC_MSG_SURFACE, HX_PRELUDE_ID + 3);
    hx_u32(&out, FC_SURFACE_ATTRIBUTES_ALL);
    hx_end(&out, at);
    hx_send_buf(fd, &out);
    hx_expect_cube_image(fd, HX_PRELUDE_ID + 2);
    hx_expect_reply_type(fd, HX_PRELUDE_ID + 3, FC_MSG_SURFACE_PART);
    hx_expect_renders(fd, HX_PRELUDE_ID + 10);
    fc_buf_free(&out);
    close(fd);
}

int main(void)
{
    hx_env env;
    if (!hx_env_start(&env, NULL))
        return hx_exit_status(test_result());
    hx_run_cases(&env, cases, sizeof cases / sizeof cases[0]);
    test_grid_past_budget(&env);
    test_good_request(&env);
    hx_env_stop(&env);
    return hx_exit_status(test_result());
}
