/* test_hardening_values.c — values outside their domains against the real
 * fluidcastd: non-finite particle data, per-particle radii outside (0, 1e6],
 * empty and oversized frames, radii,
 * cameras and image sizes, every setting's domain, unknown and duplicate
 * setting keys, and RENDER formats/AOVs (PROTOCOL.md 6.1, 7.3-7.6).
 *
 * Every offending SETTINGS starts with a valid entry (radius 0.2): the render
 * that follows on the same connection still sees the estimated radius 0.09
 * (centre depth 2.66; radius 0.2 would give 2.55), which shows the rejected
 * update left every setting unchanged. */
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "fc_frame.h"
#include "hardening_harness.h"
#include "test_scene.h"
#include "test_util.h"

#define MAX_PARTICLES 4096u
#define MAX_SIDE 64u

static const char *const daemon_args[] = {"--max-particles", "4096", "--max-image", "64x64", NULL};

/* IEEE 754 binary32 bit patterns, written out so no arithmetic produces them. */
#define QUIET_NAN 0x7fc00000u
#define SIGNALLING_NAN 0x7f800001u
#define NEGATIVE_NAN 0xffc00000u
#define PLUS_INF 0x7f800000u
#define MINUS_INF 0xff800000u

static uint32_t bits_of(float v)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    return bits;
}

/* ---- FRAME ---- */

enum { POSITIONS, DENSITY, VELOCITY, RADIUS, NO_POISON };

typedef struct frame_row {
    const char *name;
    uint64_t count;
    uint32_t attributes;
    int poisoned_array;         /* POSITIONS, DENSITY, VELOCITY, RADIUS or NO_POISON */
    size_t poisoned_value;      /* index into that array */
    uint32_t poison;            /* the value's bits */
    fc_code expected;
} frame_row;

/* Grid positions 0.1 apart, densities 1000, velocities 0, ids counting up,
 * radii 0.05 (attribute bit 3); one value replaced by the row's poison. */
static void write_frame(fc_buf *out, const frame_row *row)
{
    size_t at = hx_begin(out, FC_MSG_FRAME, HX_BAD_ID);
    hx_u64(out, row->count);
    hx_u32(out, row->attributes);
    hx_u32(out, 0);
    for (size_t i = 0; i < 3 * row->count; i++) {
        size_t particle = i / 3, axis = i % 3;
        float grid = 0.1f * (float)(axis == 0 ? particle % 16 : axis == 1 ? particle / 16 % 16 : particle / 256);
        hx_u32(out, row->poisoned_array == POSITIONS && row->poisoned_value == i ? row->poison : bits_of(grid));
    }
    for (size_t i = 0; (row->attributes & 1u) && i < row->count; i++)
        hx_u32(out, row->poisoned_array == DENSITY && row->poisoned_value == i ? row->poison : bits_of(1000.0f));
    for (size_t i = 0; (row->attributes & 2u) && i < 3 * row->count; i++)
        hx_u32(out, row->poisoned_array == VELOCITY && row->poisoned_value == i ? row->poison : 0u);
    for (size_t i = 0; (row->attributes & 4u) && i < row->count; i++)
        hx_u32(out, (uint32_t)i);
    for (size_t i = 0; (row->attributes & 8u) && i < row->count; i++)
        hx_u32(out, row->poisoned_array == RADIUS && row->poisoned_value == i ? row->poison : bits_of(0.05f));
    hx_end(out, at);
}

static const frame_row frame_rows[] = {
    {"FRAME: quiet NaN x of particle 0", 8, 0, POSITIONS, 0, QUIET_NAN, FC_ERR_INVALID_VALUE},
    {"FRAME: signalling NaN y", 8, 0, POSITIONS, 4, SIGNALLING_NAN, FC_ERR_INVALID_VALUE},
    {"FRAME: negative NaN z", 8, 0, POSITIONS, 5, NEGATIVE_NAN, FC_ERR_INVALID_VALUE},
    {"FRAME: +Inf y", 8, 7, POSITIONS, 13, PLUS_INF, FC_ERR_INVALID_VALUE},
    {"FRAME: -Inf z of the last particle", 8, 0, POSITIONS, 23, MINUS_INF, FC_ERR_INVALID_VALUE},
    {"FRAME: NaN velocity", 8, 2, VELOCITY, 7, QUIET_NAN, FC_ERR_INVALID_VALUE},
    {"FRAME: Inf velocity", 8, 7, VELOCITY, 23, MINUS_INF, FC_ERR_INVALID_VALUE},
    {"FRAME: NaN density", 8, 5, DENSITY, 3, QUIET_NAN, FC_ERR_INVALID_VALUE},
    {"FRAME: Inf density", 8, 1, DENSITY, 7, PLUS_INF, FC_ERR_INVALID_VALUE},
    {"FRAME: zero particles", 0, 0, NO_POISON, 0, 0, FC_ERR_INVALID_VALUE},
    {"FRAME: one particle beyond the quota", MAX_PARTICLES + 1, 0, NO_POISON, 0, 0, FC_ERR_LIMIT},
    {"FRAME: NaN radius", 8, 8, RADIUS, 5, QUIET_NAN, FC_ERR_INVALID_VALUE},
    {"FRAME: +Inf radius", 8, 15, RADIUS, 7, PLUS_INF, FC_ERR_INVALID_VALUE},
    {"FRAME: zero radius", 8, 12, RADIUS, 0, 0u, FC_ERR_INVALID_VALUE},
    {"FRAME: negative zero radius", 8, 8, RADIUS, 1, 0x80000000u, FC_ERR_INVALID_VALUE},
    {"FRAME: negative radius", 8, 9, RADIUS, 2, 0xbf800000u, FC_ERR_INVALID_VALUE},
    {"FRAME: radius 2e6 beyond 1e6", 8, 8, RADIUS, 3, 0x49f42400u, FC_ERR_INVALID_VALUE},
    {"FRAME: radius exactly 1e6", 8, 8, RADIUS, 3, 0x49742400u, FC_OK},
    {"FRAME: the smallest positive radius", 8, 8, RADIUS, 6, 0x00000001u, FC_OK},
    {"FRAME: attribute bit 4 unknown", 8, 16, NO_POISON, 0, 0, FC_ERR_MALFORMED},
    {"FRAME: exactly the quota, every attribute", MAX_PARTICLES, 15, NO_POISON, 0, 0, FC_OK},
    {"FRAME: x = FLT_MAX is finite", 8, 0, POSITIONS, 0, 0x7f7fffffu, FC_OK},
};

/* A huge count in a small payload: refused by the quota before anything is allocated for it. */
static void count_2_62(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_FRAME, HX_BAD_ID);
    hx_u64(out, 1ull << 62);
    hx_u32(out, 7);
    hx_u32(out, 0);
    hx_end(out, at);
}

static void run_frame_rows(hx_env *env)
{
    for (size_t i = 0; i < sizeof frame_rows / sizeof frame_rows[0]; i++) {
        const frame_row *row = &frame_rows[i];
        hx_case c = {row->name, HX_GREETED, NULL, row->expected, HX_STAYS_OPEN, false};
        fc_buf bytes;
        fc_buf_init(&bytes);
        write_frame(&bytes, row);
        hx_run_case_bytes(env, &c, &bytes);
        fc_buf_free(&bytes);
    }
    hx_run_case(env, &(hx_case){"FRAME: 2^62 particles beyond the quota", HX_GREETED, count_2_62, FC_ERR_LIMIT,
                                HX_STAYS_OPEN, false});
}

/* A bad radius is answered with a reason naming the particle, and the
 * connection renders on with its previous frame. */
static void run_radius_reason(hx_env *env)
{
    printf("case: FRAME: the reason names the particle with a bad radius\n");
    int fd = hx_connect_greeted(env, 0);
    if (fd < 0)
        return;
    const frame_row row = {"", 8, 8, RADIUS, 5, 0xc0000000u, FC_ERR_INVALID_VALUE}; /* -2 */
    fc_buf bytes;
    fc_buf_init(&bytes);
    write_frame(&bytes, &row);
    hx_send_buf(fd, &bytes);
    hx_expect_error_mentioning(fd, HX_BAD_ID, FC_ERR_INVALID_VALUE, "particle 5 has radius -2, outside (0, 1e6]");
    hx_expect_renders(fd, 100);
    fc_buf_free(&bytes);
    close(fd);
}

/* ---- SETTINGS ---- */

enum { KEY_RADIUS = 1, KEY_SMOOTHING, KEY_ITERATIONS, KEY_COLOR, KEY_ABSORPTION, KEY_IOR, KEY_FILTER_RADIUS,
       KEY_SMOOTH_SCALE, KEY_REFRACTION, KEY_SPECULAR, KEY_SHININESS, KEY_THICKNESS_SCALE, KEY_THICKNESS_BLUR,
       KEY_NOISE, KEY_FOAM, KEY_FOAM_TAU, KEY_FOAM_DECAY, KEY_DENSITY_THRESHOLD,
       KEY_KERNEL, KEY_SHADOW, KEY_EXPOSURE, KEY_COLOR_BY, KEY_COLORMAP, KEY_COLOR_RANGE,
       KEY_RESERVED_FIRST = 25, KEY_RESERVED_LAST = 31, KEY_JPEG_SUBSAMPLING = 32 };

typedef struct settings_row {
    const char *name;
    uint16_t key;
    uint16_t words;
    uint32_t value[3];          /* f32 bits or u32, as the key's type says */
    fc_code expected;
} settings_row;

#define F(v) bits_of(v)

static const settings_row settings_rows[] = {
    {"radius -1", KEY_RADIUS, 1, {0xbf800000u}, FC_ERR_INVALID_VALUE},
    {"radius -1e-30", KEY_RADIUS, 1, {0x8da24260u}, FC_ERR_INVALID_VALUE},
    {"radius NaN", KEY_RADIUS, 1, {QUIET_NAN}, FC_ERR_INVALID_VALUE},
    {"radius +Inf", KEY_RADIUS, 1, {PLUS_INF}, FC_ERR_INVALID_VALUE},
    {"radius 1000001", KEY_RADIUS, 1, {0x49742410u}, FC_ERR_INVALID_VALUE},
    {"radius 0: estimated from the frame", KEY_RADIUS, 1, {0}, FC_OK},
    {"smoothing 5", KEY_SMOOTHING, 1, {5}, FC_ERR_INVALID_VALUE},
    {"smoothing 2^32-1", KEY_SMOOTHING, 1, {UINT32_MAX}, FC_ERR_INVALID_VALUE},
    {"iterations 1001", KEY_ITERATIONS, 1, {1001}, FC_ERR_INVALID_VALUE},
    {"iterations 2^32-1", KEY_ITERATIONS, 1, {UINT32_MAX}, FC_ERR_INVALID_VALUE},
    {"fluid_color red 1.5", KEY_COLOR, 3, {0x3fc00000u, 0, 0}, FC_ERR_INVALID_VALUE},
    {"fluid_color green -0.01", KEY_COLOR, 3, {0, 0xbc23d70au, 0}, FC_ERR_INVALID_VALUE},
    {"fluid_color blue NaN", KEY_COLOR, 3, {0, 0, QUIET_NAN}, FC_ERR_INVALID_VALUE},
    {"absorption red -1", KEY_ABSORPTION, 3, {0xbf800000u, 0, 0}, FC_ERR_INVALID_VALUE},
    {"absorption green 2e6", KEY_ABSORPTION, 3, {0, 0x49f42400u, 0}, FC_ERR_INVALID_VALUE},
    {"absorption blue +Inf", KEY_ABSORPTION, 3, {0, 0, PLUS_INF}, FC_ERR_INVALID_VALUE},
    {"ior 0.99", KEY_IOR, 1, {0x3f7d70a4u}, FC_ERR_INVALID_VALUE},
    {"ior 3.01", KEY_IOR, 1, {0x4040a3d7u}, FC_ERR_INVALID_VALUE},
    {"ior NaN", KEY_IOR, 1, {QUIET_NAN}, FC_ERR_INVALID_VALUE},
    {"ior -Inf", KEY_IOR, 1, {MINUS_INF}, FC_ERR_INVALID_VALUE},
    {"filter_radius 65", KEY_FILTER_RADIUS, 1, {65}, FC_ERR_INVALID_VALUE},
    {"smooth_scale 0.3", KEY_SMOOTH_SCALE, 1, {0x3e99999au}, FC_ERR_INVALID_VALUE},
    {"refraction 1000.5", KEY_REFRACTION, 1, {0x447a2000u}, FC_ERR_INVALID_VALUE},
    {"specular -0.5", KEY_SPECULAR, 1, {0xbf000000u}, FC_ERR_INVALID_VALUE},
    {"shininess 0.5", KEY_SHININESS, 1, {0x3f000000u}, FC_ERR_INVALID_VALUE},
    {"thickness_scale 2", KEY_THICKNESS_SCALE, 1, {0x40000000u}, FC_ERR_INVALID_VALUE},
    {"thickness_blur 33", KEY_THICKNESS_BLUR, 1, {33}, FC_ERR_INVALID_VALUE},
    {"noise 10.5", KEY_NOISE, 1, {0x41280000u}, FC_ERR_INVALID_VALUE},
    {"foam -1", KEY_FOAM, 1, {0xbf800000u}, FC_ERR_INVALID_VALUE},
    {"foam_tau 0", KEY_FOAM_TAU, 1, {0}, FC_ERR_INVALID_VALUE},
    {"foam_decay 1", KEY_FOAM_DECAY, 1, {0x3f800000u}, FC_ERR_INVALID_VALUE},
    {"density_threshold -1", KEY_DENSITY_THRESHOLD, 1, {0xbf800000u}, FC_ERR_INVALID_VALUE},
    {"density_threshold +Inf", KEY_DENSITY_THRESHOLD, 1, {PLUS_INF}, FC_ERR_INVALID_VALUE},
    {"unknown setting key 0", 0, 1, {0}, FC_ERR_INVALID_VALUE},
    {"kernel 2", KEY_KERNEL, 1, {2}, FC_ERR_INVALID_VALUE},
    {"kernel 2^32-1", KEY_KERNEL, 1, {UINT32_MAX}, FC_ERR_INVALID_VALUE},
    {"shadow 2", KEY_SHADOW, 1, {2}, FC_ERR_INVALID_VALUE},
    {"exposure +Inf", KEY_EXPOSURE, 1, {PLUS_INF}, FC_ERR_INVALID_VALUE},
    {"exposure NaN", KEY_EXPOSURE, 1, {QUIET_NAN}, FC_ERR_INVALID_VALUE},
    {"color_by 3", KEY_COLOR_BY, 1, {3}, FC_ERR_INVALID_VALUE},
    {"color_by 2^32-1", KEY_COLOR_BY, 1, {UINT32_MAX}, FC_ERR_INVALID_VALUE},
    {"colormap 7", KEY_COLORMAP, 1, {7}, FC_ERR_INVALID_VALUE},
    {"colormap 2^31", KEY_COLORMAP, 1, {0x80000000u}, FC_ERR_INVALID_VALUE},
    {"color_range min NaN", KEY_COLOR_RANGE, 2, {QUIET_NAN, 0}, FC_ERR_INVALID_VALUE},
    {"color_range max +Inf", KEY_COLOR_RANGE, 2, {0, PLUS_INF}, FC_ERR_INVALID_VALUE},
    {"color_range -FLT_MAX..FLT_MAX: width overflows", KEY_COLOR_RANGE, 2, {0xff7fffffu, 0x7f7fffffu},
     FC_ERR_INVALID_VALUE},
    {"color_range with 1 word", KEY_COLOR_RANGE, 1, {0}, FC_ERR_MALFORMED},
    {"color_range with 3 words", KEY_COLOR_RANGE, 3, {0, 0x3f800000u, 0}, FC_ERR_MALFORMED},
    {"jpeg_subsampling 2", KEY_JPEG_SUBSAMPLING, 1, {2}, FC_ERR_INVALID_VALUE},
    {"jpeg_subsampling 0xFFFFFFFF", KEY_JPEG_SUBSAMPLING, 1, {0xffffffffu}, FC_ERR_INVALID_VALUE},
    {"jpeg_subsampling with 2 words", KEY_JPEG_SUBSAMPLING, 2, {1, 0}, FC_ERR_MALFORMED},
    {"reserved key 25", KEY_RESERVED_FIRST, 1, {0}, FC_ERR_INVALID_VALUE},
    {"reserved key 31", KEY_RESERVED_LAST, 1, {0}, FC_ERR_INVALID_VALUE},
    {"key 33 after the table", KEY_JPEG_SUBSAMPLING + 1, 1, {0}, FC_ERR_INVALID_VALUE},
    {"unknown setting key 25", 25, 1, {0}, FC_ERR_INVALID_VALUE},
    {"unknown setting key 65535", 0xffff, 1, {0}, FC_ERR_INVALID_VALUE},
    {"ior with 2 words", KEY_IOR, 2, {0x3fa00000u, 0}, FC_ERR_MALFORMED},
    {"fluid_color with 1 word", KEY_COLOR, 1, {0}, FC_ERR_MALFORMED},
};

static void settings_entry(fc_buf *out, uint16_t key, uint16_t words, const uint32_t *value)
{
    hx_u16(out, key);
    hx_u16(out, words);
    for (uint16_t w = 0; w < words; w++)
        hx_u32(out, value[w]);
}

/* SETTINGS { radius 0.2, the row's entry }. */
static void write_settings(fc_buf *out, const settings_row *row)
{
    static const uint32_t radius_02[1] = {0x3e4ccccdu};
    size_t at = hx_begin(out, FC_MSG_SETTINGS, HX_BAD_ID);
    hx_u32(out, 2);
    settings_entry(out, KEY_RADIUS, 1, row->key == KEY_RADIUS ? row->value : radius_02);
    if (row->key == KEY_RADIUS)
        settings_entry(out, KEY_IOR, 1, (const uint32_t[]){F(1.5f)});
    else
        settings_entry(out, row->key, row->words, row->value);
    hx_end(out, at);
}

static void run_settings_rows(hx_env *env)
{
    for (size_t i = 0; i < sizeof settings_rows / sizeof settings_rows[0]; i++) {
        const settings_row *row = &settings_rows[i];
        char name[96];
        snprintf(name, sizeof name, "SETTINGS: %s", row->name);
        hx_case c = {name, HX_GREETED, NULL, row->expected, HX_STAYS_OPEN, false};
        fc_buf bytes;
        fc_buf_init(&bytes);
        write_settings(&bytes, row);
        hx_run_case_bytes(env, &c, &bytes);
        fc_buf_free(&bytes);
    }
}

/* Structural faults of SETTINGS (7.5, checks 1-3), each after a valid radius 0.2. */
static void duplicate_key(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SETTINGS, HX_BAD_ID);
    hx_u32(out, 3);
    settings_entry(out, KEY_RADIUS, 1, (const uint32_t[]){F(0.2f)});
    settings_entry(out, KEY_IOR, 1, (const uint32_t[]){F(1.5f)});
    settings_entry(out, KEY_IOR, 1, (const uint32_t[]){F(1.4f)});
    hx_end(out, at);
}

static void more_entries_than_fit(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SETTINGS, HX_BAD_ID);
    hx_u32(out, 1000);
    settings_entry(out, KEY_RADIUS, 1, (const uint32_t[]){F(0.2f)});
    hx_end(out, at);
}

static void entry_past_payload(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SETTINGS, HX_BAD_ID);
    hx_u32(out, 2);
    settings_entry(out, KEY_RADIUS, 1, (const uint32_t[]){F(0.2f)});
    hx_u16(out, KEY_COLOR);
    hx_u16(out, 3);
    hx_f32(out, 0.5f);
    hx_end(out, at);
}

static void bytes_after_entries(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SETTINGS, HX_BAD_ID);
    hx_u32(out, 1);
    settings_entry(out, KEY_RADIUS, 1, (const uint32_t[]){F(0.2f)});
    hx_u16(out, 0);
    hx_end(out, at);
}

static void settings_without_count(fc_buf *out)
{
    hx_header(out, FC_MSG_SETTINGS, 0, HX_BAD_ID, 2);
    hx_u16(out, 0);
}

static void empty_update(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_SETTINGS, HX_BAD_ID);
    hx_u32(out, 0);
    hx_end(out, at);
}

/* ---- CAMERA ---- */

typedef struct camera_row {
    const char *name;
    uint32_t eye[3], target[3], up[3];
    uint32_t fov;
    uint32_t width, height;
    fc_code expected;
} camera_row;

#define EYE {0, 0, 0x40400000u}            /* (0, 0, 3) */
#define ORIGIN {0, 0, 0}
#define Y_UP {0, 0x3f800000u, 0}
#define FOV_40 0x42200000u

static const camera_row camera_rows[] = {
    {"image width 0", EYE, ORIGIN, Y_UP, FOV_40, 0, 32, FC_ERR_INVALID_VALUE},
    {"image height 0", EYE, ORIGIN, Y_UP, FOV_40, 32, 0, FC_ERR_INVALID_VALUE},
    {"image width beyond the limit", EYE, ORIGIN, Y_UP, FOV_40, MAX_SIDE + 1, 32, FC_ERR_LIMIT},
    {"image height beyond the limit", EYE, ORIGIN, Y_UP, FOV_40, 32, MAX_SIDE + 1, FC_ERR_LIMIT},
    {"image 2^32-1 x 2^32-1", EYE, ORIGIN, Y_UP, FOV_40, UINT32_MAX, UINT32_MAX, FC_ERR_LIMIT},
    {"eye = target", ORIGIN, ORIGIN, Y_UP, FOV_40, 32, 32, FC_ERR_INVALID_VALUE},
    {"up parallel to the view", EYE, ORIGIN, {0, 0, 0x3f800000u}, FOV_40, 32, 32, FC_ERR_INVALID_VALUE},
    {"up zero", EYE, ORIGIN, {0, 0, 0}, FOV_40, 32, 32, FC_ERR_INVALID_VALUE},
    {"fov 0", EYE, ORIGIN, Y_UP, 0, 32, 32, FC_ERR_INVALID_VALUE},
    {"fov 180", EYE, ORIGIN, Y_UP, 0x43340000u, 32, 32, FC_ERR_INVALID_VALUE},
    {"fov NaN", EYE, ORIGIN, Y_UP, QUIET_NAN, 32, 32, FC_ERR_INVALID_VALUE},
    {"eye NaN", {QUIET_NAN, 0, 0x40400000u}, ORIGIN, Y_UP, FOV_40, 32, 32, FC_ERR_INVALID_VALUE},
    {"target -Inf", EYE, {0, MINUS_INF, 0}, Y_UP, FOV_40, 32, 32, FC_ERR_INVALID_VALUE},
};

static void write_camera(fc_buf *out, const camera_row *row)
{
    size_t at = hx_begin(out, FC_MSG_CAMERA, HX_BAD_ID);
    const uint32_t *vectors[3] = {row->eye, row->target, row->up};
    for (int v = 0; v < 3; v++)
        for (int k = 0; k < 3; k++)
            hx_u32(out, vectors[v][k]);
    hx_u32(out, row->fov);
    hx_u32(out, row->width);
    hx_u32(out, row->height);
    hx_end(out, at);
}

static void run_camera_rows(hx_env *env)
{
    for (size_t i = 0; i < sizeof camera_rows / sizeof camera_rows[0]; i++) {
        const camera_row *row = &camera_rows[i];
        char name[96];
        snprintf(name, sizeof name, "CAMERA: %s", row->name);
        hx_case c = {name, HX_GREETED, NULL, row->expected, HX_STAYS_OPEN, false};
        fc_buf bytes;
        fc_buf_init(&bytes);
        write_camera(&bytes, row);
        hx_run_case_bytes(env, &c, &bytes);
        fc_buf_free(&bytes);
    }
}

/* ---- RENDER ---- */

typedef struct render_row {
    const char *name;
    bool send_frame, send_camera;   /* well-behaved FRAME / CAMERA before the RENDER */
    uint32_t format, quality, aov;
    fc_code expected;
} render_row;

static const render_row render_rows[] = {
    {"format 0", true, true, 0, 0, FC_AOV_COLOR, FC_ERR_INVALID_VALUE},
    {"format 6", true, true, 6, 0, FC_AOV_COLOR, FC_ERR_INVALID_VALUE},
    {"depth AOV as H.264", true, true, FC_FORMAT_H264, 0, FC_AOV_DEPTH, FC_ERR_INVALID_VALUE},
    {"aov 6", true, true, FC_FORMAT_EXR, 0, 6, FC_ERR_INVALID_VALUE},
    {"aov 2^32-1", true, true, FC_FORMAT_RAW, 0, UINT32_MAX, FC_ERR_INVALID_VALUE},
    {"depth AOV as PNG", true, true, FC_FORMAT_PNG, 0, FC_AOV_DEPTH, FC_ERR_INVALID_VALUE},
    {"normal AOV as JPEG", true, true, FC_FORMAT_JPEG, 90, FC_AOV_NORMAL, FC_ERR_INVALID_VALUE},
    {"thickness AOV as PNG", true, true, FC_FORMAT_PNG, 0, FC_AOV_THICKNESS, FC_ERR_INVALID_VALUE},
    {"JPEG quality 101", true, true, FC_FORMAT_JPEG, 101, FC_AOV_COLOR, FC_ERR_INVALID_VALUE},
    {"before any FRAME", false, true, FC_FORMAT_PNG, 0, FC_AOV_COLOR, FC_ERR_BAD_STATE},
    {"default view 1280x720 beyond the limit", true, false, FC_FORMAT_PNG, 0, FC_AOV_COLOR, FC_ERR_LIMIT},
};

static void write_render(fc_buf *out, const render_row *row)
{
    fc_error err;
    if (row->send_frame) {
        fc_frame cube;
        CHECK_CODE(fc_test_cube_frame(&cube, &err), FC_OK);
        CHECK_CODE(fc_wire_write_frame(out, HX_PRELUDE_ID, &cube, &err), FC_OK);
        fc_frame_free(&cube);
    }
    if (row->send_camera) {
        fc_camera camera;
        fc_test_front_camera(HX_IMAGE_SIDE, HX_IMAGE_SIDE, &camera);
        CHECK_CODE(fc_wire_write_camera(out, HX_PRELUDE_ID + 1, &camera, &err), FC_OK);
    }
    size_t at = hx_begin(out, FC_MSG_RENDER, HX_BAD_ID);
    hx_u32(out, row->format);
    hx_u32(out, row->quality);
    hx_u32(out, row->aov);
    hx_end(out, at);
}

static void run_render_rows(hx_env *env)
{
    for (size_t i = 0; i < sizeof render_rows / sizeof render_rows[0]; i++) {
        const render_row *row = &render_rows[i];
        char name[96];
        snprintf(name, sizeof name, "RENDER: %s", row->name);
        hx_case c = {name, HX_GREETED, NULL, row->expected, HX_STAYS_OPEN, false};
        fc_buf bytes;
        fc_buf_init(&bytes);
        write_render(&bytes, row);
        hx_run_case_bytes(env, &c, &bytes);
        fc_buf_free(&bytes);
    }
}

static const hx_case settings_structure_cases[] = {
    {"SETTINGS: duplicate key", HX_GREETED, duplicate_key, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"SETTINGS: 1000 entries in 8 bytes", HX_GREETED, more_entries_than_fit, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"SETTINGS: entry runs past the payload", HX_GREETED, entry_past_payload, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"SETTINGS: bytes after the last entry", HX_GREETED, bytes_after_entries, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"SETTINGS: payload ends inside the count", HX_GREETED, settings_without_count, FC_ERR_MALFORMED, HX_STAYS_OPEN,
     false},
    {"SETTINGS: empty update", HX_GREETED, empty_update, FC_OK, HX_STAYS_OPEN, false},
};

int main(void)
{
    hx_env env;
    if (!hx_env_start(&env, daemon_args))
        return hx_exit_status(test_result());
    run_radius_reason(&env);
    run_frame_rows(&env);
    run_settings_rows(&env);
    hx_run_cases(&env, settings_structure_cases, sizeof settings_structure_cases / sizeof settings_structure_cases[0]);
    run_camera_rows(&env);
    run_render_rows(&env);
    hx_env_stop(&env);
    return hx_exit_status(test_result());
}
