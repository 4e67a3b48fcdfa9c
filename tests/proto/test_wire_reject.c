/* test_wire_reject.c — every rule of PROTOCOL.md that rejects input, with the
 * exact code it must produce. Built with AddressSanitizer and UBSan: each
 * payload is copied into a heap block of exactly its size, so a decoder that
 * reads one byte too far aborts the test. */
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "test_util.h"
#include "wire.h"

/* A heap copy of exactly n bytes (ASan flags any access beyond it). */
static uint8_t *exact_copy(const uint8_t *p, size_t n)
{
    uint8_t *copy = malloc(n ? n : 1);
    if (copy && n)
        memcpy(copy, p, n);
    return copy;
}

/* Decodes a payload as the message `type`, as the receiver would. */
static fc_code decode(fc_msg_type type, const uint8_t *p, size_t n, fc_error *err)
{
    fc_hello hello;
    fc_welcome welcome;
    fc_frame frame = {0};
    fc_camera camera;
    fc_settings settings;
    fc_render_request render;
    fc_image_reply image;
    fc_error error;
    fc_code code = FC_ERR_UNKNOWN_TYPE;
    fc_settings_default(&settings);
    switch (type) {
    case FC_MSG_HELLO: code = fc_wire_read_hello(p, n, &hello, err); break;
    case FC_MSG_WELCOME: code = fc_wire_read_welcome(p, n, &welcome, err); break;
    case FC_MSG_FRAME: code = fc_wire_read_frame(p, n, UINT64_MAX, &frame, err); break;
    case FC_MSG_CAMERA: code = fc_wire_read_camera(p, n, &camera, err); break;
    case FC_MSG_SETTINGS: code = fc_wire_read_settings(p, n, &settings, err); break;
    case FC_MSG_RENDER: code = fc_wire_read_render(p, n, &render, err); break;
    case FC_MSG_IMAGE: code = fc_wire_read_image(p, n, &image, err); break;
    case FC_MSG_ERROR: code = fc_wire_read_error(p, n, &error, err); break;
    case FC_MSG_GOODBYE: code = fc_wire_read_goodbye(p, n, err); break;
    default: break; /* messages beyond the core nine have their own tests */
    }
    fc_frame_free(&frame);
    return code;
}

static fc_code decode_copy(fc_msg_type type, const uint8_t *p, size_t n, fc_error *err)
{
    uint8_t *copy = exact_copy(p, n);
    fc_code code = decode(type, copy, n, err);
    free(copy);
    return code;
}

/* One valid message of every type, encoded into b (one message per buffer). */
static void encode_sample(fc_msg_type type, fc_buf *b)
{
    static float positions[6] = {0, 0, 0, 1, 1, 1}, density[2] = {1, 2}, velocity[6] = {1, 2, 3, 4, 5, 6};
    static uint32_t ids[2] = {7, 8};
    static const uint8_t data[5] = {1, 2, 3, 4, 5};
    fc_error err;
    fc_code code = FC_ERR_UNKNOWN_TYPE;
    switch (type) {
    case FC_MSG_HELLO: {
        fc_hello m = {.version_min = 1, .version_max = 1, .client_name = "test"};
        code = fc_wire_write_hello(b, 1, &m, &err);
        break;
    }
    case FC_MSG_WELCOME: {
        fc_welcome m = {.version = 1, .limits = {16, 64, 64, 4096}, .server_version = "s", .renderer = "gpu"};
        code = fc_wire_write_welcome(b, 1, &m, &err);
        break;
    }
    case FC_MSG_FRAME: {
        fc_frame m = {.count = 2, .positions = positions, .density = density, .velocity = velocity, .ids = ids};
        code = fc_wire_write_frame(b, 1, &m, &err);
        break;
    }
    case FC_MSG_CAMERA: {
        fc_camera m = {.eye = {0, -5, 0}, .target = {0, 0, 0}, .up = {0, 0, 1}, .fov_y_deg = 45, .width = 8,
                       .height = 8};
        code = fc_wire_write_camera(b, 1, &m, &err);
        break;
    }
    case FC_MSG_SETTINGS: {
        fc_settings m;
        fc_settings_default(&m);
        code = fc_wire_write_settings(b, 1, &m, &err);
        break;
    }
    case FC_MSG_RENDER: {
        fc_render_request m = {FC_FORMAT_EXR, 0, FC_AOV_THICKNESS};
        code = fc_wire_write_render(b, 1, &m, &err);
        break;
    }
    case FC_MSG_IMAGE: {
        fc_image_reply m = {.width = 1, .height = 1, .format = FC_FORMAT_PNG, .data = data, .size = sizeof data};
        for (int s = 0; s < FC_STAGE_COUNT; s++)
            m.stage_ms[s] = (float)s;
        code = fc_wire_write_image(b, 1, &m, &err);
        break;
    }
    case FC_MSG_ERROR: {
        fc_error m;
        fc_error_set(&m, FC_ERR_LIMIT, "too many");
        code = fc_wire_write_error(b, 1, &m, &err);
        break;
    }
    case FC_MSG_GOODBYE: code = fc_wire_write_goodbye(b, 1, &err); break;
    default: break;
    }
    CHECK_CODE(code, FC_OK);
}

static void test_every_truncation_is_malformed(void)
{
    for (int type = FC_MSG_HELLO; type <= FC_MSG_GOODBYE; type++) {
        fc_buf b;
        fc_buf_init(&b);
        encode_sample((fc_msg_type)type, &b);
        const uint8_t *payload = b.data + FC_WIRE_HEADER_SIZE;
        size_t n = b.len - FC_WIRE_HEADER_SIZE;
        fc_error err;
        CHECK_MSG(decode_copy((fc_msg_type)type, payload, n, &err) == FC_OK, "type %d: %s", type, err.message);
        for (size_t cut = 0; cut < n; cut++) {
            fc_code code = decode_copy((fc_msg_type)type, payload, cut, &err);
            CHECK_MSG(code == FC_ERR_MALFORMED, "type %d cut at %zu of %zu: code %d (%s)", type, cut, n, (int)code,
                      err.message);
        }
        /* One byte too many: every message but HELLO (which later versions may extend) is exact. */
        uint8_t *longer = malloc(n + 1);
        if (n)
            memcpy(longer, payload, n);
        longer[n] = 0;
        fc_code code = decode((fc_msg_type)type, longer, n + 1, &err);
        CHECK_MSG(code == (type == FC_MSG_HELLO ? FC_OK : FC_ERR_MALFORMED), "type %d with a trailing byte: %d",
                  type, (int)code);
        free(longer);
        fc_buf_free(&b);
    }
}

static void test_header_rules(void)
{
    const uint8_t good[16] = {'F', 'C', 'S', 'T', 1, 0, 0, 0, 5, 0, 0, 0, 0x10, 0, 0, 0};
    uint8_t h[16];
    fc_msg_header out;
    fc_error err;
    CHECK_CODE(fc_wire_decode_header(good, 16, &out, &err), FC_OK);

    memcpy(h, good, 16);
    h[3] = 'X';
    CHECK_CODE(fc_wire_decode_header(h, 16, &out, &err), FC_ERR_BAD_MAGIC);
    CHECK_CODE(fc_wire_decode_header(good, 15, &out, &err), FC_ERR_TOO_LARGE);
    CHECK_CODE(err.code, FC_ERR_TOO_LARGE);

    memcpy(h, good, 16);
    h[7] = 0x80; /* flags 0x8000 */
    CHECK_CODE(fc_wire_decode_header(h, 16, &out, &err), FC_ERR_MALFORMED);
    /* The header is still filled in, so the receiver can skip the payload and carry on. */
    CHECK(out.flags == 0x8000 && out.length == 16 && out.request_id == 5);

    /* Bad magic wins over every other fault: nothing else in the header can be trusted. */
    h[0] = 0;
    CHECK_CODE(fc_wire_decode_header(h, 0, &out, &err), FC_ERR_BAD_MAGIC);
    /* A too-large length closes the connection even when the flags are also wrong. */
    memcpy(h, good, 16);
    h[6] = 1;
    CHECK_CODE(fc_wire_decode_header(h, 15, &out, &err), FC_ERR_TOO_LARGE);
}

/* FRAME fixed part: count, attributes, reserved; followed by `data` bytes of zeros. */
static fc_code read_frame_fixed(uint64_t count, uint32_t attributes, uint32_t reserved, size_t data,
                                uint64_t max_particles, fc_frame *frame, fc_error *err)
{
    size_t n = 16 + data;
    uint8_t *p = calloc(n, 1);
    for (int i = 0; i < 8; i++)
        p[i] = (uint8_t)(count >> (8 * i));
    for (int i = 0; i < 4; i++) {
        p[8 + i] = (uint8_t)(attributes >> (8 * i));
        p[12 + i] = (uint8_t)(reserved >> (8 * i));
    }
    fc_code code = fc_wire_read_frame(p, n, max_particles, frame, err);
    free(p);
    return code;
}

static void test_frame_rules(void)
{
    fc_frame frame = {0};
    fc_error err;
    CHECK_CODE(read_frame_fixed(2, 0, 0, 24, 2, &frame, &err), FC_OK);
    CHECK(frame.count == 2 && frame.positions && !frame.density && !frame.velocity && !frame.ids);
    fc_frame_free(&frame);

    /* Bit 3 is the radius (PROTOCOL.md 7.3); bit 4 and up are unknown. */
    CHECK_CODE(read_frame_fixed(2, 1u << 4, 0, 24, 2, &frame, &err), FC_ERR_MALFORMED);
    CHECK(strstr(err.message, "unknown attribute bits 0x10") != NULL);
    CHECK_CODE(read_frame_fixed(2, 1u << 31, 0, 24, 2, &frame, &err), FC_ERR_MALFORMED);
    /* Bit 3 with its 4 bytes per particle: the layout holds, the zero radii are out of their domain. */
    CHECK_CODE(read_frame_fixed(2, FC_ATTR_RADIUS, 0, 24, 2, &frame, &err), FC_ERR_MALFORMED);
    CHECK_CODE(read_frame_fixed(2, FC_ATTR_RADIUS, 0, 32, 2, &frame, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "particle 0 has radius 0") != NULL, "\"%s\"", err.message);
    CHECK_CODE(read_frame_fixed(2, 0, 1, 24, 2, &frame, &err), FC_ERR_MALFORMED);
    CHECK_CODE(read_frame_fixed(0, 0, 0, 0, 2, &frame, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(read_frame_fixed(3, 0, 0, 36, 2, &frame, &err), FC_ERR_LIMIT);
    /* The limit is checked before sizes and allocation: a huge count with no data is LIMIT, not MALFORMED. */
    CHECK_CODE(read_frame_fixed(1ull << 62, 0, 0, 0, 1u << 24, &frame, &err), FC_ERR_LIMIT);
    CHECK_CODE(read_frame_fixed(2, 0, 0, 23, 2, &frame, &err), FC_ERR_MALFORMED);
    CHECK_CODE(read_frame_fixed(2, 0, 0, 25, 2, &frame, &err), FC_ERR_MALFORMED);
    CHECK_CODE(read_frame_fixed(2, FC_ATTR_DENSITY, 0, 24, 2, &frame, &err), FC_ERR_MALFORMED);
    /* (2^60 + 1) x 16 bytes wraps to 16 in 64 bits; a wrapping check would accept it. */
    CHECK_CODE(read_frame_fixed((1ull << 60) + 1, FC_ATTR_DENSITY, 0, 16, UINT64_MAX, &frame, &err),
               FC_ERR_MALFORMED);
    CHECK(frame.count == 0 && frame.positions == NULL);
}

static void test_frame_non_finite_values(void)
{
    const struct {
        uint32_t attributes;
        size_t float_index; /* into the payload's float arrays after the fixed part */
        float value;
        const char *what;
    } cases[] = {
        {0, 4, NAN, "particle 1 has a non-finite position"},
        {0, 0, INFINITY, "particle 0 has a non-finite position"},
        {FC_ATTR_DENSITY, 6 + 1, -INFINITY, "particle 1 has a non-finite density"},
        {FC_ATTR_VELOCITY, 6 + 2, NAN, "particle 0 has a non-finite velocity"},
        {FC_ATTR_VELOCITY | FC_ATTR_DENSITY, 6 + 2 + 3, NAN, "particle 1 has a non-finite velocity"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        fc_frame in = {0}, out = {0};
        fc_error err;
        CHECK_CODE(fc_frame_alloc(&in, 2, cases[c].attributes, &err), FC_OK);
        memset(in.positions, 0, 6 * sizeof(float));
        if (in.density)
            memset(in.density, 0, 2 * sizeof(float));
        if (in.velocity)
            memset(in.velocity, 0, 6 * sizeof(float));
        fc_buf b;
        fc_buf_init(&b);
        CHECK_CODE(fc_wire_write_frame(&b, 1, &in, &err), FC_OK);
        float value = cases[c].value;
        memcpy(b.data + FC_WIRE_HEADER_SIZE + 16 + 4 * cases[c].float_index, &value, 4);
        CHECK_CODE(decode_copy(FC_MSG_FRAME, b.data + FC_WIRE_HEADER_SIZE, b.len - FC_WIRE_HEADER_SIZE, &err),
                   FC_ERR_INVALID_VALUE);
        CHECK_MSG(strstr(err.message, cases[c].what) != NULL, "case %zu: \"%s\"", c, err.message);
        CHECK_CODE(fc_wire_read_frame(b.data + FC_WIRE_HEADER_SIZE, b.len - FC_WIRE_HEADER_SIZE, 2, &out, &err),
                   FC_ERR_INVALID_VALUE);
        CHECK(out.positions == NULL && out.count == 0);
        fc_buf_free(&b);
        fc_frame_free(&in);
    }
}

/* Radii outside (0, 1e6] are refused, naming the first particle that has one;
 * the limits themselves are accepted. */
static void test_frame_radius_domain(void)
{
    const struct {
        float value;
        fc_code expected;
        const char *what;
    } cases[] = {
        {NAN, FC_ERR_INVALID_VALUE, "particle 2 has a non-finite radius"},
        {INFINITY, FC_ERR_INVALID_VALUE, "particle 2 has a non-finite radius"},
        {-INFINITY, FC_ERR_INVALID_VALUE, "particle 2 has a non-finite radius"},
        {0.0f, FC_ERR_INVALID_VALUE, "particle 2 has radius 0, outside (0, 1e6]"},
        {-0.0f, FC_ERR_INVALID_VALUE, "particle 2 has radius -0, outside (0, 1e6]"},
        {-1.0f, FC_ERR_INVALID_VALUE, "particle 2 has radius -1, outside (0, 1e6]"},
        {1.0000001e6f, FC_ERR_INVALID_VALUE, "particle 2 has radius 1e+06, outside (0, 1e6]"},
        {3e38f, FC_ERR_INVALID_VALUE, "particle 2 has radius 3e+38, outside (0, 1e6]"},
        {1e6f, FC_OK, NULL},
        {0x1p-149f, FC_OK, NULL}, /* the smallest positive float: tiny, but a size */
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        fc_frame in = {0}, out = {0};
        fc_error err = {0};
        CHECK_CODE(fc_frame_alloc(&in, 4, FC_ATTR_RADIUS | FC_ATTR_IDS, &err), FC_OK);
        memset(in.positions, 0, 12 * sizeof(float));
        for (int i = 0; i < 4; i++) {
            in.ids[i] = (uint32_t)i;
            in.radius[i] = 0.5f;
        }
        in.radius[2] = cases[c].value;
        in.radius[3] = NAN; /* a later bad radius: the first one is named */
        if (cases[c].expected == FC_OK)
            in.radius[3] = 0.5f;
        CHECK_CODE(fc_frame_validate(&in, &err), cases[c].expected);
        fc_buf b;
        fc_buf_init(&b);
        CHECK_CODE(fc_wire_write_frame(&b, 1, &in, &err), FC_OK);
        CHECK_CODE(fc_wire_read_frame(b.data + FC_WIRE_HEADER_SIZE, b.len - FC_WIRE_HEADER_SIZE, 4, &out, &err),
                   cases[c].expected);
        if (cases[c].what)
            CHECK_MSG(strstr(err.message, cases[c].what) != NULL, "case %zu: \"%s\"", c, err.message);
        CHECK(cases[c].expected == FC_OK ? out.radius != NULL && out.radius[2] == cases[c].value
                                         : out.positions == NULL && out.count == 0);
        fc_frame_free(&out);
        fc_buf_free(&b);
        fc_frame_free(&in);
    }
}

static fc_code read_camera_with(void (*change)(fc_camera *), fc_error *err)
{
    fc_camera cam = {.eye = {0, -5, 0}, .target = {0, 0, 0}, .up = {0, 0, 1}, .fov_y_deg = 45, .width = 8,
                     .height = 8};
    change(&cam);
    fc_buf b;
    fc_buf_init(&b);
    fc_wire_write_camera(&b, 1, &cam, err);
    fc_code code = decode_copy(FC_MSG_CAMERA, b.data + FC_WIRE_HEADER_SIZE, b.len - FC_WIRE_HEADER_SIZE, err);
    fc_buf_free(&b);
    return code;
}

static void cam_unchanged(fc_camera *c) { (void)c; }
static void cam_eye_nan(fc_camera *c) { c->eye[1] = NAN; }
static void cam_up_inf(fc_camera *c) { c->up[0] = INFINITY; }
static void cam_eye_is_target(fc_camera *c) { c->eye[1] = 0; }
static void cam_up_parallel(fc_camera *c) { c->up[1] = 2, c->up[2] = 0; }
static void cam_up_zero(fc_camera *c) { c->up[2] = 0; }
static void cam_fov_zero(fc_camera *c) { c->fov_y_deg = 0; }
static void cam_fov_180(fc_camera *c) { c->fov_y_deg = 180; }
static void cam_width_zero(fc_camera *c) { c->width = 0; }
static void cam_height_zero(fc_camera *c) { c->height = 0; }

static void test_camera_rules(void)
{
    fc_error err;
    CHECK_CODE(read_camera_with(cam_unchanged, &err), FC_OK);
    void (*invalid[])(fc_camera *) = {cam_eye_nan, cam_up_inf, cam_eye_is_target, cam_up_parallel, cam_up_zero,
                                      cam_fov_zero, cam_fov_180, cam_width_zero, cam_height_zero};
    for (size_t i = 0; i < sizeof invalid / sizeof invalid[0]; i++)
        CHECK_MSG(read_camera_with(invalid[i], &err) == FC_ERR_INVALID_VALUE, "case %zu", i);
}

/* A SETTINGS payload from a list of u16/u32 fields; `kinds` spells each field: 'h' u16, 'w' u32/f32 bits. */
static size_t build(uint8_t *out, const char *kinds, const uint32_t *values)
{
    size_t n = 0;
    for (size_t i = 0; kinds[i]; i++) {
        int bytes = kinds[i] == 'h' ? 2 : 4;
        for (int k = 0; k < bytes; k++)
            out[n++] = (uint8_t)(values[i] >> (8 * k));
    }
    return n;
}

static uint32_t f32_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

static fc_code read_settings_built(const char *kinds, const uint32_t *values, fc_settings *s, fc_error *err)
{
    uint8_t payload[256];
    size_t n = build(payload, kinds, values);
    uint8_t *copy = exact_copy(payload, n);
    fc_code code = fc_wire_read_settings(copy, n, s, err);
    free(copy);
    return code;
}

static void test_settings_rules(void)
{
    fc_settings s, before;
    fc_settings_default(&s);
    before = s;
    fc_error err;

    const uint32_t iterations_7[] = {1, 3, 1, 7};
    CHECK_CODE(read_settings_built("whhw", iterations_7, &s, &err), FC_OK);
    CHECK(s.iterations == 7);
    s = before;

    const uint32_t unknown_key[] = {1, 25, 1, 0};
    CHECK_CODE(read_settings_built("whhw", unknown_key, &s, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "25") != NULL, "\"%s\" does not name key 25", err.message);
    /* Colouring by speed over an empty range: each entry alone is valid, the merged settings are not. */
    const uint32_t empty_range[] = {2, 22, 1, FC_COLOR_BY_SPEED, 24, 2, f32_bits(2.0f), f32_bits(2.0f)};
    CHECK_CODE(read_settings_built("whhwhhww", empty_range, &s, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "color_range") != NULL, "\"%s\" does not name color_range", err.message);
    CHECK(memcmp(&s, &before, sizeof s) == 0);
    const uint32_t range_one_word[] = {1, 24, 1, 0};
    CHECK_CODE(read_settings_built("whhw", range_one_word, &s, &err), FC_ERR_MALFORMED);
    const uint32_t key_zero[] = {1, 0, 1, 0};
    CHECK_CODE(read_settings_built("whhw", key_zero, &s, &err), FC_ERR_INVALID_VALUE);
    const uint32_t wrong_words[] = {1, 1, 2, f32_bits(1), f32_bits(1)};
    CHECK_CODE(read_settings_built("whhww", wrong_words, &s, &err), FC_ERR_MALFORMED);
    const uint32_t color_one_word[] = {1, 4, 1, f32_bits(1)};
    CHECK_CODE(read_settings_built("whhw", color_one_word, &s, &err), FC_ERR_MALFORMED);
    const uint32_t words_past_end[] = {1, 6, 2, f32_bits(1.5f)};
    CHECK_CODE(read_settings_built("whhw", words_past_end, &s, &err), FC_ERR_MALFORMED);
    const uint32_t too_many_entries[] = {2, 6, 1, f32_bits(1.5f)};
    CHECK_CODE(read_settings_built("whhw", too_many_entries, &s, &err), FC_ERR_MALFORMED);
    const uint32_t huge_entry_count[] = {0xFFFFFFFFu, 6, 1, f32_bits(1.5f)};
    CHECK_CODE(read_settings_built("whhw", huge_entry_count, &s, &err), FC_ERR_MALFORMED);
    const uint32_t duplicate[] = {2, 6, 1, f32_bits(1.5f), 6, 1, f32_bits(1.4f)};
    CHECK_CODE(read_settings_built("whhwhhw", duplicate, &s, &err), FC_ERR_MALFORMED);
    const uint32_t unknown_smoothing[] = {1, 2, 1, 5};
    CHECK_CODE(read_settings_built("whhw", unknown_smoothing, &s, &err), FC_ERR_INVALID_VALUE);
    const uint32_t huge_smoothing[] = {1, 2, 1, 0xFFFFFFFFu};
    CHECK_CODE(read_settings_built("whhw", huge_smoothing, &s, &err), FC_ERR_INVALID_VALUE);

    /* Values out of their domain, each after a valid entry (smoothing none): the whole update is refused. */
    const struct {
        uint16_t key;
        uint32_t words[3];
        uint16_t n;
    } out_of_domain[] = {
        {1, {f32_bits(-0.5f)}, 1},           {1, {f32_bits(NAN)}, 1},
        {1, {f32_bits(2e6f)}, 1},            {3, {1001}, 1},
        {4, {0, f32_bits(1.5f), 0}, 3},      {4, {f32_bits(-0.1f), 0, 0}, 3},
        {5, {0, 0, f32_bits(INFINITY)}, 3},  {5, {f32_bits(-1), 0, 0}, 3},
        {6, {f32_bits(0.99f)}, 1},           {6, {f32_bits(3.01f)}, 1},
        {22, {3}, 1},                        {23, {7}, 1},
        {24, {f32_bits(NAN), 0}, 2},         {24, {0, f32_bits(-INFINITY)}, 2},
    };
    for (size_t i = 0; i < sizeof out_of_domain / sizeof out_of_domain[0]; i++) {
        uint32_t values[9] = {2, 2, 1, FC_SMOOTHING_NONE, out_of_domain[i].key, out_of_domain[i].n};
        char kinds[16] = "whhwhh";
        for (uint16_t w = 0; w < out_of_domain[i].n; w++) {
            values[6 + w] = out_of_domain[i].words[w];
            strcat(kinds, "w");
        }
        CHECK_MSG(read_settings_built(kinds, values, &s, &err) == FC_ERR_INVALID_VALUE, "case %zu", i);
        CHECK_MSG(memcmp(&s, &before, sizeof s) == 0, "case %zu changed the settings", i);
    }
    /* Structural failure after a valid entry also leaves the target as it was. */
    const uint32_t then_truncated[] = {2, 2, 1, FC_SMOOTHING_NONE, 6, 1};
    CHECK_CODE(read_settings_built("whhwhh", then_truncated, &s, &err), FC_ERR_MALFORMED);
    CHECK(memcmp(&s, &before, sizeof s) == 0);

    /* The domain edges themselves are accepted. */
    const uint32_t edges[] = {5, 1, 1, f32_bits(1e6f), 3, 1, 1000, 4, 3, f32_bits(1), 0, f32_bits(1),
                              6, 1, f32_bits(3), 5, 3, 0, f32_bits(1e6f), 0};
    CHECK_CODE(read_settings_built("whhwhhwhhwwwhhwhhwww", edges, &s, &err), FC_OK);
    CHECK(s.radius == 1e6f && s.iterations == 1000 && s.ior == 3.0f && s.absorption[1] == 1e6f);
}

static fc_code read_render_values(uint32_t format, uint32_t quality, uint32_t aov, fc_error *err)
{
    const uint32_t values[] = {format, quality, aov};
    uint8_t payload[12];
    size_t n = build(payload, "www", values);
    return decode_copy(FC_MSG_RENDER, payload, n, err);
}

static void test_render_rules(void)
{
    fc_error err;
    CHECK_CODE(read_render_values(FC_FORMAT_RAW, 0, FC_AOV_DEPTH, &err), FC_OK);
    CHECK_CODE(read_render_values(FC_FORMAT_EXR, 100, FC_AOV_SMOOTHED_DEPTH, &err), FC_OK);
    CHECK_CODE(read_render_values(0, 0, FC_AOV_COLOR, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(read_render_values(FC_FORMAT_H264, 0, FC_AOV_COLOR, &err), FC_OK);
    CHECK_CODE(read_render_values(6, 0, FC_AOV_COLOR, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(read_render_values(FC_FORMAT_H264, 0, FC_AOV_NORMAL, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(read_render_values(FC_FORMAT_JPEG, 101, FC_AOV_COLOR, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(read_render_values(FC_FORMAT_EXR, 0, 6, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(read_render_values(FC_FORMAT_PNG, 0, FC_AOV_DEPTH, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(read_render_values(FC_FORMAT_JPEG, 0, FC_AOV_THICKNESS, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(read_render_values(FC_FORMAT_PNG, 0, FC_AOV_SMOOTHED_DEPTH, &err), FC_ERR_INVALID_VALUE);
}

static void test_image_rules(void)
{
    fc_error err;
    /* 1x1 PNG colour, no stages, data size 2 with 2 bytes: valid. */
    const uint32_t ok[] = {1, 1, 1, 0, 0, 2, 0, 0xBBAA};
    uint8_t payload[64];
    size_t n = build(payload, "wwwwwwwh", ok);
    CHECK_CODE(decode_copy(FC_MSG_IMAGE, payload, n, &err), FC_OK);

    const uint32_t size_mismatch[] = {1, 1, 1, 0, 0, 3, 0, 0xAAAA};
    n = build(payload, "wwwwwwwh", size_mismatch);
    CHECK_CODE(decode_copy(FC_MSG_IMAGE, payload, n, &err), FC_ERR_MALFORMED);
    const uint32_t huge_size[] = {1, 1, 1, 0, 0, 2, 0x80000000u, 0xAAAA};
    n = build(payload, "wwwwwwwh", huge_size);
    CHECK_CODE(decode_copy(FC_MSG_IMAGE, payload, n, &err), FC_ERR_MALFORMED);
    const uint32_t huge_stage_count[] = {1, 1, 1, 0, 0xFFFFFFFFu, 0, 0};
    n = build(payload, "wwwwwww", huge_stage_count);
    CHECK_CODE(decode_copy(FC_MSG_IMAGE, payload, n, &err), FC_ERR_MALFORMED);
    const uint32_t unknown_format[] = {1, 1, 9, 0, 0, 0, 0};
    n = build(payload, "wwwwwww", unknown_format);
    CHECK_CODE(decode_copy(FC_MSG_IMAGE, payload, n, &err), FC_ERR_INVALID_VALUE);
}

static void test_string_rules(void)
{
    fc_error err;
    /* HELLO whose name holds a NUL. */
    const uint8_t with_nul[] = {1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 3, 0, 'a', 0, 'b'};
    CHECK_CODE(decode_copy(FC_MSG_HELLO, with_nul, sizeof with_nul, &err), FC_ERR_MALFORMED);
    /* Length 0xFFFF with three bytes present. */
    const uint8_t past_end[] = {1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0xFF, 0xFF, 'a', 'b', 'c'};
    CHECK_CODE(decode_copy(FC_MSG_HELLO, past_end, sizeof past_end, &err), FC_ERR_MALFORMED);
    /* An empty name is fine. */
    const uint8_t empty[] = {1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    CHECK_CODE(decode_copy(FC_MSG_HELLO, empty, sizeof empty, &err), FC_OK);
}

static void test_error_and_goodbye_rules(void)
{
    fc_error err;
    const uint8_t code_zero[] = {0, 0, 0, 0, 0, 0};
    CHECK_CODE(decode_copy(FC_MSG_ERROR, code_zero, sizeof code_zero, &err), FC_ERR_MALFORMED);
    const uint8_t local_code[] = {100, 0, 0, 0, 0, 0};
    CHECK_CODE(decode_copy(FC_MSG_ERROR, local_code, sizeof local_code, &err), FC_ERR_MALFORMED);
    /* A wire code this version does not name is passed on as it is. */
    const uint8_t future_code[] = {50, 0, 0, 0, 1, 0, '!'};
    fc_error received;
    CHECK_CODE(fc_wire_read_error(future_code, sizeof future_code, &received, &err), FC_OK);
    CHECK(received.code == 50 && strcmp(received.message, "!") == 0);

    const uint8_t one_byte[] = {0};
    CHECK_CODE(decode_copy(FC_MSG_GOODBYE, one_byte, sizeof one_byte, &err), FC_ERR_MALFORMED);
}

int main(void)
{
    test_every_truncation_is_malformed();
    test_header_rules();
    test_frame_rules();
    test_frame_non_finite_values();
    test_frame_radius_domain();
    test_camera_rules();
    test_settings_rules();
    test_render_rules();
    test_image_rules();
    test_string_rules();
    test_error_and_goodbye_rules();
    return test_result();
}
