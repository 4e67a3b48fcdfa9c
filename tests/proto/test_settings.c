/* test_settings.c — the render settings: their defaults, the domain of every
 * field (fc_settings_validate and SETTINGS both refuse with INVALID_VALUE), and
 * every SETTINGS key (PROTOCOL.md's table) against hand-encoded bytes. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "test_util.h"
#include "wire.h"

/* ---- a SETTINGS payload written byte by byte, independent of the encoder ---- */

typedef struct payload {
    uint8_t bytes[512];
    size_t n;
} payload;

static void put_le(payload *p, uint32_t v, int bytes)
{
    for (int k = 0; k < bytes; k++)
        p->bytes[p->n++] = (uint8_t)(v >> (8 * k));
}

static uint32_t f32_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* A payload of one entry: key, word count, words. */
static payload one_entry(uint16_t key, const uint32_t *words, uint16_t count)
{
    payload p = {.n = 0};
    put_le(&p, 1, 4);
    put_le(&p, key, 2);
    put_le(&p, count, 2);
    for (uint16_t i = 0; i < count; i++)
        put_le(&p, words[i], 4);
    return p;
}

/* Decodes from an exact-size heap copy, so a read past the end leaves the allocation (ASan, valgrind). */
static fc_code read_payload(const payload *p, fc_settings *s, fc_error *err)
{
    uint8_t *copy = malloc(p->n);
    memcpy(copy, p->bytes, p->n);
    fc_code code = fc_wire_read_settings(copy, p->n, s, err);
    free(copy);
    return code;
}

/* ---- defaults ---- */

static void test_defaults(void)
{
    fc_settings s;
    fc_settings_default(&s);
    fc_error err;
    CHECK_CODE(fc_settings_validate(&s, &err), FC_OK);
    CHECK(s.radius == 0.0f && s.smoothing == FC_SMOOTHING_NARROW && s.iterations == fc_smoothing_default_iterations(FC_SMOOTHING_NARROW));
    CHECK(s.filter_radius == 0 && s.smooth_scale == 1.0f);
    CHECK(s.ior == 1.33f && s.refraction == 0.25f && s.specular == 1.5f && s.shininess == 400.0f);
    CHECK(s.thickness_scale == 0.25f && s.thickness_blur == 2);
    CHECK(s.noise == 0.0f && s.foam == 0.0f && s.foam_tau == 0.5f && s.foam_decay == 0.85f);
    CHECK(s.density_threshold == 0.0f);
    CHECK(s.kernel == FC_KERNEL_SPHERE && s.shadow == 1 && s.exposure == 0.0f);
    CHECK(s.color_by == FC_COLOR_BY_NONE && s.colormap == FC_COLORMAP_VIRIDIS);
    CHECK(s.color_range[0] == 0.0f && s.color_range[1] == 1.0f);
}

/* ---- every key, one at a time ---- */

typedef struct key_case {
    uint16_t key;
    uint16_t words;
    uint32_t value[3];                 /* wire words */
    void (*expect)(fc_settings *s);    /* applies the same change to the expected settings */
} key_case;

static void expect_radius(fc_settings *s) { s->radius = 0.125f; }
static void expect_smoothing(fc_settings *s) { s->smoothing = FC_SMOOTHING_BINOMIAL; }
static void expect_iterations(fc_settings *s) { s->iterations = 7; }
static void expect_fluid_color(fc_settings *s) { memcpy(s->fluid_color, (float[3]){1.0f, 0.5f, 0.25f}, 12); }
static void expect_absorption(fc_settings *s) { memcpy(s->absorption, (float[3]){3.0f, 0.0f, 100.0f}, 12); }
static void expect_ior(fc_settings *s) { s->ior = 1.5f; }
static void expect_filter_radius(fc_settings *s) { s->filter_radius = 12; }
static void expect_smooth_scale(fc_settings *s) { s->smooth_scale = 0.25f; }
static void expect_refraction(fc_settings *s) { s->refraction = 250.0f; }
static void expect_specular(fc_settings *s) { s->specular = 2.5f; }
static void expect_shininess(fc_settings *s) { s->shininess = 512.0f; }
static void expect_thickness_scale(fc_settings *s) { s->thickness_scale = 0.5f; }
static void expect_thickness_blur(fc_settings *s) { s->thickness_blur = 9; }
static void expect_noise(fc_settings *s) { s->noise = 0.75f; }
static void expect_foam(fc_settings *s) { s->foam = 3.0f; }
static void expect_foam_tau(fc_settings *s) { s->foam_tau = 0.02f; }
static void expect_foam_decay(fc_settings *s) { s->foam_decay = 0.5f; }
static void expect_density_threshold(fc_settings *s) { s->density_threshold = 600.0f; }
static void expect_kernel(fc_settings *s) { s->kernel = FC_KERNEL_ANISOTROPIC; }
static void expect_shadow(fc_settings *s) { s->shadow = 0; }
static void expect_exposure(fc_settings *s) { s->exposure = -1.5f; }
static void expect_color_by(fc_settings *s) { s->color_by = FC_COLOR_BY_DENSITY; }
static void expect_colormap(fc_settings *s) { s->colormap = FC_COLORMAP_TURBO; }
static void expect_color_range(fc_settings *s) { memcpy(s->color_range, (float[2]){-2.0f, 0.5f}, 8); }
static void expect_jpeg_subsampling(fc_settings *s) { s->jpeg_subsampling = FC_JPEG_SUBSAMPLING_YUV420; }
static void expect_spray_neighbours(fc_settings *s) { s->spray_neighbours = 5; }
static void expect_surface(fc_settings *s) { s->surface = FC_SURFACE_MODE_MESH; }
static void expect_surface_cell(fc_settings *s) { s->surface_cell = 1.5f; }
static void expect_surface_kernel(fc_settings *s) { s->surface_kernel = FC_SURFACE_KERNEL_SPH; }
static void expect_surface_smoothing(fc_settings *s) { s->surface_smoothing = 10; }
static void expect_contact_shadow(fc_settings *s) { s->contact_shadow = 0.25f; }
static void expect_depth_dimming(fc_settings *s) { s->depth_dimming = 0.5f; }
static void expect_aerated_foam(fc_settings *s) { s->aerated_foam = 0.5f; }

static const key_case key_cases[] = {
    {1, 1, {0x3E000000u}, expect_radius},                             /* 0.125f */
    {2, 1, {3}, expect_smoothing},
    {3, 1, {7}, expect_iterations},
    {4, 3, {0x3F800000u, 0x3F000000u, 0x3E800000u}, expect_fluid_color}, /* 1, 0.5, 0.25 */
    {5, 3, {0x40400000u, 0x00000000u, 0x42C80000u}, expect_absorption},  /* 3, 0, 100 */
    {6, 1, {0x3FC00000u}, expect_ior},                                /* 1.5f */
    {7, 1, {12}, expect_filter_radius},
    {8, 1, {0x3E800000u}, expect_smooth_scale},                       /* 0.25f */
    {9, 1, {0x437A0000u}, expect_refraction},                         /* 250f */
    {10, 1, {0x40200000u}, expect_specular},                          /* 2.5f */
    {11, 1, {0x44000000u}, expect_shininess},                         /* 512f */
    {12, 1, {0x3F000000u}, expect_thickness_scale},                   /* 0.5f */
    {13, 1, {9}, expect_thickness_blur},
    {14, 1, {0x3F400000u}, expect_noise},                             /* 0.75f */
    {15, 1, {0x40400000u}, expect_foam},                              /* 3f */
    {16, 1, {0x3CA3D70Au}, expect_foam_tau},                          /* 0.02f */
    {17, 1, {0x3F000000u}, expect_foam_decay},                        /* 0.5f */
    {18, 1, {0x44160000u}, expect_density_threshold},                 /* 600f */
    {19, 1, {1}, expect_kernel},
    {20, 1, {0}, expect_shadow},
    {21, 1, {0xBFC00000u}, expect_exposure},                          /* -1.5f */
    {22, 1, {2}, expect_color_by},
    {23, 1, {6}, expect_colormap},
    {24, 2, {0xC0000000u, 0x3F000000u}, expect_color_range},          /* -2, 0.5 */
    {32, 1, {1}, expect_jpeg_subsampling},                            /* 25-31 reserved */
    {40, 1, {5}, expect_spray_neighbours},                            /* 33-39: the surface's look */
    {45, 1, {1}, expect_surface},                                     /* 41-44: reserved */
    {46, 1, {0x3FC00000u}, expect_surface_cell},                      /* 1.5f */
    {47, 1, {1}, expect_surface_kernel},
    {48, 1, {10}, expect_surface_smoothing},
    {57, 1, {0x3E800000u}, expect_contact_shadow},                   /* 0.25f */
    {58, 1, {0x3F000000u}, expect_depth_dimming},                    /* 0.5f */
    {59, 1, {0x3F000000u}, expect_aerated_foam},                     /* 0.5f */
};
#define KEY_COUNT (sizeof key_cases / sizeof key_cases[0])

static void test_each_key_decodes(void)
{
    for (size_t i = 0; i < KEY_COUNT; i++) {
        const key_case *c = &key_cases[i];
        fc_settings got, expected;
        fc_settings_default(&got);
        fc_settings_default(&expected);
        c->expect(&expected);
        CHECK_MSG(memcmp(&got, &expected, sizeof got) != 0, "key %u: the test value is the default", c->key);
        payload p = one_entry(c->key, c->value, c->words);
        fc_error err;
        CHECK_MSG(read_payload(&p, &got, &err) == FC_OK, "key %u: %s", c->key, err.message);
        CHECK_MSG(memcmp(&got, &expected, sizeof got) == 0, "key %u set the wrong field or value", c->key);
    }
}

/* The encoder writes every key once, in key order, with the layout of the
 * table, and each entry carries exactly the words key_cases expects. */
static void test_encoder_layout(void)
{
    fc_settings s;
    fc_settings_default(&s);
    for (size_t i = 0; i < KEY_COUNT; i++)
        key_cases[i].expect(&s);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_settings(&b, 9, &s, &err), FC_OK);
    /* 38 words: two colours of 3, thirty of 1, a range of 2 */
    const size_t payload_size = 4 + KEY_COUNT * 4 + 4 * 38;
    CHECK_MSG(b.len == FC_WIRE_HEADER_SIZE + payload_size, "%zu bytes", b.len);
    if (b.len != FC_WIRE_HEADER_SIZE + payload_size) {
        fc_buf_free(&b);
        return;
    }
    payload expected = {.n = 0};
    put_le(&expected, (uint32_t)KEY_COUNT, 4);
    for (size_t i = 0; i < KEY_COUNT; i++) {
        put_le(&expected, key_cases[i].key, 2);
        put_le(&expected, key_cases[i].words, 2);
        for (uint16_t w = 0; w < key_cases[i].words; w++)
            put_le(&expected, key_cases[i].value[w], 4);
    }
    CHECK(expected.n == payload_size);
    CHECK(memcmp(b.data + FC_WIRE_HEADER_SIZE, expected.bytes, payload_size) == 0);
    fc_buf_free(&b);
}

/* Encode -> decode onto different settings restores every field. */
static void test_roundtrip(void)
{
    fc_settings in, out;
    fc_settings_default(&in);
    for (size_t i = 0; i < KEY_COUNT; i++)
        key_cases[i].expect(&in);
    memset(&out, 0, sizeof out);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_settings(&b, 1, &in, &err), FC_OK);
    CHECK_CODE(fc_wire_read_settings(b.data + FC_WIRE_HEADER_SIZE, b.len - FC_WIRE_HEADER_SIZE, &out, &err), FC_OK);
    CHECK(memcmp(&in, &out, sizeof in) == 0);
    fc_buf_free(&b);
}

/* ---- domains ---- */

typedef struct domain_case {
    uint16_t key;
    uint32_t bits;           /* the value, as its wire word (the first word for colours) */
    const char *name;        /* the field the error message must name */
} domain_case;

static const domain_case rejected[] = {
    {1, 0xBF000000u, "radius"},              /* -0.5 */
    {1, 0x7FC00000u, "radius"},              /* NaN */
    {3, 1001, "iterations"},
    {4, 0x3FC00000u, "fluid_color"},         /* 1.5 */
    {5, 0xBF800000u, "absorption"},          /* -1 */
    {6, 0x3F7D70A4u, "ior"},                 /* 0.99 */
    {7, 65, "filter_radius"},
    {8, 0x3F400000u, "smooth_scale"},        /* 0.75 */
    {8, 0x00000000u, "smooth_scale"},        /* 0 */
    {8, 0x40000000u, "smooth_scale"},        /* 2 */
    {9, 0xBF800000u, "refraction"},          /* -1 */
    {9, 0x447A2000u, "refraction"},          /* 1000.5 */
    {9, 0x7F800000u, "refraction"},          /* +inf */
    {10, 0xBDCCCCCDu, "specular"},           /* -0.1 */
    {10, 0x41200001u, "specular"},           /* just above 10 */
    {11, 0x3F000000u, "shininess"},          /* 0.5 */
    {11, 0x461C4400u, "shininess"},          /* 10001 */
    {12, 0x3E000000u, "thickness_scale"},    /* 0.125 */
    {13, 33, "thickness_blur"},
    {14, 0xBA83126Fu, "noise"},              /* -0.001 */
    {14, 0x41300000u, "noise"},              /* 11 */
    {15, 0x41300000u, "foam"},               /* 11 */
    {15, 0x7FC00000u, "foam"},               /* NaN */
    {16, 0x00000000u, "foam_tau"},           /* 0 */
    {16, 0xBF800000u, "foam_tau"},           /* -1 */
    {16, 0x7F800000u, "foam_tau"},           /* +inf */
    {17, 0x3F800000u, "foam_decay"},         /* 1 */
    {17, 0xBDCCCCCDu, "foam_decay"},         /* -0.1 */
    {18, 0xBF800000u, "density_threshold"},  /* -1 */
    {18, 0x7F800000u, "density_threshold"},  /* +inf */
    {19, 2, "kernel"},
    {20, 2, "shadow"},
    {21, 0x41880000u, "exposure"},           /* 17 */
    {21, 0xC1880000u, "exposure"},           /* -17 */
    {21, 0x7FC00000u, "exposure"},           /* NaN */
    {22, 3, "color_by"},
    {22, 0xFFFFFFFFu, "color_by"},
    {23, 7, "colormap"},
    {24, 0x7FC00000u, "color_range"},        /* NaN, 0 */
    {24, 0xFF800000u, "color_range"},        /* -inf, 0 */
    {32, 2, "jpeg_subsampling"},
    {32, 0xFFFFFFFFu, "jpeg_subsampling"},
    {40, 65, "spray_neighbours"},
};

/* The entry for case c: colours carry the value in their first word. */
static payload domain_payload(const domain_case *c)
{
    uint32_t words[3] = {c->bits, 0, 0};
    uint16_t count = (c->key == 4 || c->key == 5) ? 3 : c->key == 24 ? 2 : 1;
    return one_entry(c->key, words, count);
}

static void test_domains_rejected_on_the_wire(void)
{
    for (size_t i = 0; i < sizeof rejected / sizeof rejected[0]; i++) {
        const domain_case *c = &rejected[i];
        fc_settings s, before;
        fc_settings_default(&s);
        before = s;
        payload p = domain_payload(c);
        fc_error err;
        CHECK_MSG(read_payload(&p, &s, &err) == FC_ERR_INVALID_VALUE, "case %zu (key %u): %s", i, c->key,
                  err.message);
        CHECK_MSG(strstr(err.message, c->name) != NULL, "case %zu: \"%s\" does not name %s", i, err.message, c->name);
        CHECK_MSG(memcmp(&s, &before, sizeof s) == 0, "case %zu changed the settings", i);
    }
}

/* fc_settings_validate on its own, for values the wire cannot carry (an enum beyond its range). */
static void test_validate_rejects_unknown_smoothing(void)
{
    fc_settings s;
    fc_settings_default(&s);
    s.smoothing = (fc_smoothing)5;
    fc_error err;
    CHECK_CODE(fc_settings_validate(&s, &err), FC_ERR_INVALID_VALUE);
    const uint32_t five = 5;
    payload p = one_entry(2, &five, 1);
    fc_settings_default(&s);
    CHECK_CODE(read_payload(&p, &s, &err), FC_ERR_INVALID_VALUE);
    CHECK(s.smoothing == FC_SMOOTHING_NARROW);
}

/* Each smoothing method is accepted. */
static void test_every_smoothing_accepted(void)
{
    for (uint32_t m = FC_SMOOTHING_NONE; m <= FC_SMOOTHING_NARROW; m++) {
        fc_settings s;
        fc_settings_default(&s);
        payload p = one_entry(2, &m, 1);
        fc_error err;
        CHECK_MSG(read_payload(&p, &s, &err) == FC_OK && s.smoothing == (fc_smoothing)m, "smoothing %u", m);
    }
}

static void test_domain_edges_accepted(void)
{
    const struct {
        uint16_t key;
        uint32_t bits;
    } edges[] = {
        {7, 64},          {7, 0},           {8, 0x3F000000u}, {8, 0x3F800000u},          /* 64, 0, 0.5, 1 */
        {9, 0},           {9, 0x447A0000u},                                              /* 0, 1000 */
        {10, 0},          {10, 0x41200000u},                                             /* 0, 10 */
        {11, 0x3F800000u}, {11, 0x461C4000u},                                            /* 1, 10000 */
        {12, 0x3E800000u}, {13, 32},        {13, 0},                                     /* 0.25, 32, 0 */
        {14, 0},          {14, 0x41200000u}, {15, 0}, {15, 0x41200000u},                 /* 0, 10 */
        {16, 0x00000001u}, {16, 0x7F7FFFFFu},                                            /* tiniest, largest */
        {17, 0},          {17, 0x3F7FFFFFu},                                             /* 0, just below 1 */
        {18, 0},          {18, 0x7F7FFFFFu},
        {19, 0},          {19, 1},          {20, 0},          {20, 1},                   /* sphere, anisotropic, off, on */
        {21, 0x41800000u}, {21, 0xC1800000u},                                            /* 16, -16 */
        {22, 0},          {22, 1},          {22, 2},          {23, 0},    {23, 6},       /* none .. density, maps */
    };
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; i++) {
        fc_settings s;
        fc_settings_default(&s);
        payload p = one_entry(edges[i].key, &edges[i].bits, 1);
        fc_error err;
        CHECK_MSG(read_payload(&p, &s, &err) == FC_OK, "edge %zu (key %u): %s", i, edges[i].key, err.message);
    }
}

/* color_range: finite words and a finite width always; min < max once an
 * attribute colours (zeroed settings, which colour nothing, stay valid). */
static void test_color_range_domain(void)
{
    const struct {
        float lo, hi;
        fc_color_by by;
        fc_code expected;
    } cases[] = {
        {0.0f, INFINITY, FC_COLOR_BY_NONE, FC_ERR_INVALID_VALUE},
        {-FLT_MAX, FLT_MAX, FC_COLOR_BY_NONE, FC_ERR_INVALID_VALUE},    /* the width overflows */
        {1.0f, 1.0f, FC_COLOR_BY_SPEED, FC_ERR_INVALID_VALUE},
        {3.0f, 2.0f, FC_COLOR_BY_DENSITY, FC_ERR_INVALID_VALUE},
        {3.0f, 2.0f, FC_COLOR_BY_NONE, FC_OK},
        {0.0f, 0.0f, FC_COLOR_BY_NONE, FC_OK},
        {-1e30f, 1e30f, FC_COLOR_BY_SPEED, FC_OK},
        {0.0f, 1e-30f, FC_COLOR_BY_SPEED, FC_OK},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        fc_settings s, before;
        fc_settings_default(&s);
        s.color_by = cases[i].by;
        before = s;
        const uint32_t words[2] = {f32_bits(cases[i].lo), f32_bits(cases[i].hi)};
        payload p = one_entry(24, words, 2);
        fc_error err;
        fc_code code = read_payload(&p, &s, &err);
        CHECK_MSG(code == cases[i].expected, "range case %zu: %s", i, code == FC_OK ? "accepted" : err.message);
        if (code != FC_OK) {
            CHECK_MSG(strstr(err.message, "color_range") != NULL, "\"%s\" does not name color_range", err.message);
            CHECK(memcmp(&s, &before, sizeof s) == 0);
        }
    }
    /* Setting the attribute onto an empty range is refused as well. */
    fc_settings s;
    fc_settings_default(&s);
    s.color_range[1] = 0.0f;
    const uint32_t speed = FC_COLOR_BY_SPEED;
    payload p = one_entry(22, &speed, 1);
    fc_error err;
    CHECK_CODE(read_payload(&p, &s, &err), FC_ERR_INVALID_VALUE);
    CHECK(s.color_by == FC_COLOR_BY_NONE);
}

static void test_unknown_key_after_the_table(void)
{
    const uint32_t zero = 0;
    fc_settings s;
    fc_settings_default(&s);
    fc_error err;
    /* The reserved numbers between the defined keys, and those after the last, are unknown. */
    static const uint16_t unknown[] = {25, 31, 33, 63, 64, 65535};
    for (size_t i = 0; i < sizeof unknown / sizeof unknown[0]; i++) {
        payload u = one_entry(unknown[i], &zero, 1);
        CHECK_CODE(read_payload(&u, &s, &err), FC_ERR_INVALID_VALUE);
        char key[8];
        snprintf(key, sizeof key, "%u", unknown[i]);
        CHECK_MSG(strstr(err.message, key) != NULL, "\"%s\" does not name key %s", err.message, key);
    }
    payload p;
    /* A scale is one word: two is a layout error, not a domain error. */
    const uint32_t two_words[2] = {f32_bits(1.0f), f32_bits(1.0f)};
    p = one_entry(8, two_words, 2);
    CHECK_CODE(read_payload(&p, &s, &err), FC_ERR_MALFORMED);
}

int main(void)
{
    test_defaults();
    test_each_key_decodes();
    test_encoder_layout();
    test_roundtrip();
    test_domains_rejected_on_the_wire();
    test_validate_rejects_unknown_smoothing();
    test_every_smoothing_accepted();
    test_domain_edges_accepted();
    test_color_range_domain();
    test_unknown_key_after_the_table();
    return test_result();
}
