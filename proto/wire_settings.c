/* wire_settings.c — the SETTINGS message: a list of key/value entries, so a
 * client can update some settings and leave the others as they are. */
#include "wire.h"

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
    KEY_END
} setting_key;

#define SETTINGS_ENTRY_COUNT (KEY_END - 1)
#define ENTRY_HEADER_SIZE 4u
#define WORD_SIZE 4u

static const struct {
    const char *name;
    uint16_t words; /* 4-byte words of the value */
} settings_keys[KEY_END] = {
    [KEY_RADIUS] = {"radius", 1},
    [KEY_SMOOTHING] = {"smoothing", 1},
    [KEY_ITERATIONS] = {"iterations", 1},
    [KEY_FLUID_COLOR] = {"fluid_color", 3},
    [KEY_ABSORPTION] = {"absorption", 3},
    [KEY_IOR] = {"ior", 1},
};

static void put_entry_header(fc_buf *out, setting_key key)
{
    wire_put_u16(out, (uint16_t)key);
    wire_put_u16(out, settings_keys[key].words);
}

fc_code fc_wire_write_settings(fc_buf *out, uint32_t request_id, const fc_settings *m, fc_error *err)
{
    uint32_t length = 4;
    for (int key = KEY_RADIUS; key < KEY_END; key++)
        length += ENTRY_HEADER_SIZE + WORD_SIZE * settings_keys[key].words;
    size_t start = wire_begin_message(out, FC_MSG_SETTINGS, request_id, length);
    wire_put_u32(out, SETTINGS_ENTRY_COUNT);
    put_entry_header(out, KEY_RADIUS);
    wire_put_f32(out, m->radius);
    put_entry_header(out, KEY_SMOOTHING);
    wire_put_u32(out, (uint32_t)m->smoothing);
    put_entry_header(out, KEY_ITERATIONS);
    wire_put_u32(out, m->iterations);
    put_entry_header(out, KEY_FLUID_COLOR);
    wire_put_f32_array(out, m->fluid_color, 3);
    put_entry_header(out, KEY_ABSORPTION);
    wire_put_f32_array(out, m->absorption, 3);
    put_entry_header(out, KEY_IOR);
    wire_put_f32(out, m->ior);
    return wire_end_message(out, start, err);
}

/* Reads one entry's value into *s; the entry header is already read and checked. */
static void read_value(wire_reader *r, setting_key key, fc_settings *s)
{
    const char *name = settings_keys[key].name;
    switch (key) {
    case KEY_RADIUS: s->radius = wire_get_f32(r, name); break;
    case KEY_SMOOTHING: {
        uint32_t smoothing = wire_get_u32(r, name);
        /* Checked here, before the value becomes an enum it may not fit. */
        if (smoothing > FC_SMOOTHING_CURVATURE)
            wire_fail(r, FC_ERR_INVALID_VALUE, "unknown smoothing %u", smoothing);
        else
            s->smoothing = (fc_smoothing)smoothing;
        break;
    }
    case KEY_ITERATIONS: s->iterations = wire_get_u32(r, name); break;
    case KEY_FLUID_COLOR: wire_get_f32_array(r, s->fluid_color, 3, name); break;
    case KEY_ABSORPTION: wire_get_f32_array(r, s->absorption, 3, name); break;
    case KEY_IOR: s->ior = wire_get_f32(r, name); break;
    case KEY_END: break;
    }
}

/* Reads one entry, checking its structure before its key so that a truncated
 * message is always MALFORMED. `seen` collects the keys read so far. */
static void read_entry(wire_reader *r, fc_settings *s, uint32_t *seen)
{
    uint16_t key = wire_get_u16(r, "key");
    uint16_t words = wire_get_u16(r, "word count");
    if (r->code != FC_OK)
        return;
    if (words > wire_remaining(r) / WORD_SIZE)
        wire_fail(r, FC_ERR_MALFORMED, "entry for key %u runs past the payload", key);
    else if (key < KEY_RADIUS || key >= KEY_END)
        wire_fail(r, FC_ERR_INVALID_VALUE, "unknown setting key %u", key);
    else if (words != settings_keys[key].words)
        wire_fail(r, FC_ERR_MALFORMED, "%s takes %u words, not %u", settings_keys[key].name,
                  settings_keys[key].words, words);
    else if (*seen & (1u << key))
        wire_fail(r, FC_ERR_MALFORMED, "%s appears twice", settings_keys[key].name);
    else {
        *seen |= 1u << key;
        read_value(r, (setting_key)key, s);
    }
}

fc_code fc_wire_read_settings(const uint8_t *p, size_t n, fc_settings *m, fc_error *err)
{
    /* Entries are merged into a copy so that any failure leaves *m untouched. */
    fc_settings merged = *m;
    uint32_t seen = 0;
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
