/* wire_settings.c — the SETTINGS message: a list of key/value entries, so a
 * client can update some settings and leave the others as they are. Each key
 * names one field of fc_settings (table in PROTOCOL.md). */
#include "wire.h"

#include <stdbool.h>
#include <stddef.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "wire_io.h"

typedef enum setting_key {
    KEY_RADIUS = 1,
    KEY_SMOOTHING = 2,
    KEY_ITERATIONS = 3,
    KEY_FLUID_COLOR = 4,
    KEY_ABSORPTION = 5,
    KEY_IOR = 6,
    KEY_FILTER_RADIUS = 7,
    KEY_SMOOTH_SCALE = 8,
    KEY_REFRACTION = 9,
    KEY_SPECULAR = 10,
    KEY_SHININESS = 11,
    KEY_THICKNESS_SCALE = 12,
    KEY_THICKNESS_BLUR = 13,
    KEY_NOISE = 14,
    KEY_FOAM = 15,
    KEY_FOAM_TAU = 16,
    KEY_FOAM_DECAY = 17,
    KEY_DENSITY_THRESHOLD = 18,
    KEY_KERNEL = 19,
    KEY_SHADOW = 20,
    KEY_EXPOSURE = 21,
    KEY_COLOR_BY = 22,
    KEY_COLORMAP = 23,
    KEY_COLOR_RANGE = 24,
    /* 25-31 are reserved (PROTOCOL.md 7.5): unknown until defined. */
    KEY_JPEG_SUBSAMPLING = 32,
    KEY_END
} setting_key;

#define ENTRY_HEADER_SIZE 4u
#define WORD_SIZE 4u

/* How a key's words map onto its field. */
typedef enum value_kind {
    VALUE_F32 = 1,      /* `words` floats */
    VALUE_U32,          /* one unsigned integer */
    VALUE_ENUM          /* one u32 that must name a value of the field's enum: 0..enum_max */
} value_kind;

typedef struct key_spec {
    const char *name;
    uint16_t words;     /* 4-byte words of the value */
    value_kind kind;
    size_t offset;      /* of the field in fc_settings */
    uint32_t enum_max;  /* VALUE_ENUM: the largest value */
} key_spec;

_Static_assert(sizeof(fc_smoothing) == sizeof(int) && sizeof(fc_kernel) == sizeof(int) &&
                   sizeof(fc_color_by) == sizeof(int) && sizeof(fc_colormap) == sizeof(int) &&
                   sizeof(fc_jpeg_subsampling) == sizeof(int),
               "VALUE_ENUM fields are accessed as int");
/* read_entry marks the keys seen in one u64. */
_Static_assert(KEY_END <= 64, "more keys than bits in the seen mask");

#define FIELD(key, field, words, kind) [key] = {#field, words, kind, offsetof(fc_settings, field), 0}
#define ENUM_FIELD(key, field, max) [key] = {#field, 1, VALUE_ENUM, offsetof(fc_settings, field), max}

static const key_spec settings_keys[KEY_END] = {
    FIELD(KEY_RADIUS, radius, 1, VALUE_F32),
    ENUM_FIELD(KEY_SMOOTHING, smoothing, FC_SMOOTHING_NARROW),
    FIELD(KEY_ITERATIONS, iterations, 1, VALUE_U32),
    FIELD(KEY_FLUID_COLOR, fluid_color, 3, VALUE_F32),
    FIELD(KEY_ABSORPTION, absorption, 3, VALUE_F32),
    FIELD(KEY_IOR, ior, 1, VALUE_F32),
    FIELD(KEY_FILTER_RADIUS, filter_radius, 1, VALUE_U32),
    FIELD(KEY_SMOOTH_SCALE, smooth_scale, 1, VALUE_F32),
    FIELD(KEY_REFRACTION, refraction, 1, VALUE_F32),
    FIELD(KEY_SPECULAR, specular, 1, VALUE_F32),
    FIELD(KEY_SHININESS, shininess, 1, VALUE_F32),
    FIELD(KEY_THICKNESS_SCALE, thickness_scale, 1, VALUE_F32),
    FIELD(KEY_THICKNESS_BLUR, thickness_blur, 1, VALUE_U32),
    FIELD(KEY_NOISE, noise, 1, VALUE_F32),
    FIELD(KEY_FOAM, foam, 1, VALUE_F32),
    FIELD(KEY_FOAM_TAU, foam_tau, 1, VALUE_F32),
    FIELD(KEY_FOAM_DECAY, foam_decay, 1, VALUE_F32),
    FIELD(KEY_DENSITY_THRESHOLD, density_threshold, 1, VALUE_F32),
    ENUM_FIELD(KEY_KERNEL, kernel, FC_KERNEL_ANISOTROPIC),
    FIELD(KEY_SHADOW, shadow, 1, VALUE_U32),
    FIELD(KEY_EXPOSURE, exposure, 1, VALUE_F32),
    ENUM_FIELD(KEY_COLOR_BY, color_by, FC_COLOR_BY_DENSITY),
    ENUM_FIELD(KEY_COLORMAP, colormap, FC_COLORMAP_TURBO),
    FIELD(KEY_COLOR_RANGE, color_range, 2, VALUE_F32),
    ENUM_FIELD(KEY_JPEG_SUBSAMPLING, jpeg_subsampling, FC_JPEG_SUBSAMPLING_YUV420),
};

/* A key the table defines; the reserved numbers between defined keys have no name. */
static bool key_defined(uint32_t key)
{
    return key >= KEY_RADIUS && key < KEY_END && settings_keys[key].name != NULL;
}

/* The field a key names, for reading (writer) and for filling in (reader). */
static const void *field_in(const fc_settings *s, const key_spec *spec)
{
    return (const char *)s + spec->offset;
}

static void *field_at(fc_settings *s, const key_spec *spec)
{
    return (char *)s + spec->offset;
}

static void put_entry(fc_buf *out, setting_key key, const fc_settings *m)
{
    const key_spec *spec = &settings_keys[key];
    wire_put_u16(out, (uint16_t)key);
    wire_put_u16(out, spec->words);
    switch (spec->kind) {
    case VALUE_F32: wire_put_f32_array(out, field_in(m, spec), spec->words); break;
    case VALUE_U32: wire_put_u32(out, *(const uint32_t *)field_in(m, spec)); break;
    /* Enums are stored as the compiler's int-sized enum type, written as u32. */
    case VALUE_ENUM: wire_put_u32(out, (uint32_t)*(const int *)field_in(m, spec)); break;
    }
}

fc_code fc_wire_write_settings(fc_buf *out, uint32_t request_id, const fc_settings *m, fc_error *err)
{
    uint32_t length = 4, entries = 0;
    for (int key = KEY_RADIUS; key < KEY_END; key++) {
        if (key_defined((uint32_t)key)) {
            length += ENTRY_HEADER_SIZE + WORD_SIZE * settings_keys[key].words;
            entries++;
        }
    }
    size_t start = wire_begin_message(out, FC_MSG_SETTINGS, request_id, length);
    wire_put_u32(out, entries);
    for (int key = KEY_RADIUS; key < KEY_END; key++)
        if (key_defined((uint32_t)key))
            put_entry(out, (setting_key)key, m);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_write_settings_none(fc_buf *out, uint32_t request_id, fc_error *err)
{
    size_t start = wire_begin_message(out, FC_MSG_SETTINGS, request_id, 4);
    wire_put_u32(out, 0);
    return wire_end_message(out, start, err);
}

/* Reads one entry's value into *s; the entry header is already read and checked. */
static void read_value(wire_reader *r, setting_key key, fc_settings *s)
{
    const key_spec *spec = &settings_keys[key];
    switch (spec->kind) {
    case VALUE_F32: wire_get_f32_array(r, field_at(s, spec), spec->words, spec->name); break;
    case VALUE_U32: *(uint32_t *)field_at(s, spec) = wire_get_u32(r, spec->name); break;
    case VALUE_ENUM: {
        uint32_t value = wire_get_u32(r, spec->name);
        /* Checked here, before the value becomes an enum it may not fit. */
        if (r->code == FC_OK && value > spec->enum_max)
            wire_fail(r, FC_ERR_INVALID_VALUE, "unknown %s %u", spec->name, value);
        else
            *(int *)field_at(s, spec) = (int)value;
        break;
    }
    }
}

/* Reads one entry, checking its structure before its key so that a truncated
 * message is always MALFORMED. `seen` collects the keys read so far. */
static void read_entry(wire_reader *r, fc_settings *s, uint64_t *seen)
{
    uint16_t key = wire_get_u16(r, "key");
    uint16_t words = wire_get_u16(r, "word count");
    if (r->code != FC_OK)
        return;
    if (words > wire_remaining(r) / WORD_SIZE)
        wire_fail(r, FC_ERR_MALFORMED, "entry for key %u runs past the payload", key);
    else if (!key_defined(key))
        wire_fail(r, FC_ERR_INVALID_VALUE, "unknown setting key %u", key);
    else if (words != settings_keys[key].words)
        wire_fail(r, FC_ERR_MALFORMED, "%s takes %u words, not %u", settings_keys[key].name,
                  settings_keys[key].words, words);
    else if (*seen & ((uint64_t)1 << key))
        wire_fail(r, FC_ERR_MALFORMED, "%s appears twice", settings_keys[key].name);
    else {
        *seen |= (uint64_t)1 << key;
        read_value(r, (setting_key)key, s);
    }
}

fc_code fc_wire_read_settings(const uint8_t *p, size_t n, fc_settings *m, fc_error *err)
{
    /* Entries are merged into a copy so that any failure leaves *m untouched. */
    fc_settings merged = *m;
    uint64_t seen = 0;
    wire_reader r = wire_reader_start(p, n, "SETTINGS", err);
    uint32_t entries = wire_get_u32(&r, "entry count");
    if (r.code == FC_OK && entries > wire_remaining(&r) / ENTRY_HEADER_SIZE)
        wire_fail(&r, FC_ERR_MALFORMED, "%u entries do not fit the payload", entries);
    for (uint32_t i = 0; i < entries && r.code == FC_OK; i++)
        read_entry(&r, &merged, &seen);
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    fc_code code = fc_settings_validate(&merged, err);
    if (code != FC_OK)
        return code;
    *m = merged;
    return FC_OK;
}
