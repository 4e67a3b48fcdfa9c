/* wire_settings.c — the SETTINGS message: a list of key/value entries, so a
 * client can update some settings and leave the others as they are. Each key
 * names one field of fc_settings (fc_settings.c's table; PROTOCOL.md 7.5). */
#include "wire.h"

#include <stdbool.h>
#include <stddef.h>

#include "fc_error.h"
#include "fc_settings.h"
#include "wire_io.h"

#define ENTRY_HEADER_SIZE 4u
#define WORD_SIZE 4u
/* read_entry marks the keys seen in one u64: a larger key is unknown. */
#define MAX_KEY 63u

static bool is_float(const fc_setting_spec *spec)
{
    return spec->type == FC_SETTING_FLOAT || spec->type == FC_SETTING_SCALE;
}

static void put_entry(fc_buf *out, const fc_setting_spec *spec, const fc_settings *m)
{
    wire_put_u16(out, spec->key);
    wire_put_u16(out, (uint16_t)spec->count);
    const void *field = fc_setting_field_const(spec, m);
    if (is_float(spec))
        wire_put_f32_array(out, field, spec->count);
    else
        wire_put_u32(out, *(const uint32_t *)field);
}

fc_code fc_wire_write_settings(fc_buf *out, uint32_t request_id, const fc_settings *m, fc_error *err)
{
    size_t count;
    const fc_setting_spec *table = fc_settings_table(&count);
    uint32_t length = 4;
    for (size_t i = 0; i < count; i++)
        length += ENTRY_HEADER_SIZE + WORD_SIZE * table[i].count;
    size_t start = wire_begin_message(out, FC_MSG_SETTINGS, request_id, length);
    wire_put_u32(out, (uint32_t)count);
    for (size_t i = 0; i < count; i++)
        put_entry(out, &table[i], m);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_write_settings_none(fc_buf *out, uint32_t request_id, fc_error *err)
{
    size_t start = wire_begin_message(out, FC_MSG_SETTINGS, request_id, 4);
    wire_put_u32(out, 0);
    return wire_end_message(out, start, err);
}

/* Reads one entry's value into *s; the entry header is already read and checked. */
static void read_value(wire_reader *r, const fc_setting_spec *spec, fc_settings *s)
{
    void *field = fc_setting_field(spec, s);
    if (is_float(spec)) {
        wire_get_f32_array(r, field, spec->count, spec->name);
        return;
    }
    uint32_t value = wire_get_u32(r, spec->name);
    /* A choice is checked here, before the value becomes an enum it may not fit. */
    if (r->code == FC_OK && spec->type == FC_SETTING_CHOICE && value >= fc_setting_choice_count(spec))
        wire_fail(r, FC_ERR_INVALID_VALUE, "unknown %s %u", spec->name, value);
    else
        *(uint32_t *)field = value;
}

/* Reads one entry, checking its structure before its key so that a truncated
 * message is always MALFORMED. `seen` collects the keys read so far. */
static void read_entry(wire_reader *r, fc_settings *s, uint64_t *seen)
{
    uint16_t key = wire_get_u16(r, "key");
    uint16_t words = wire_get_u16(r, "word count");
    if (r->code != FC_OK)
        return;
    const fc_setting_spec *spec = key <= MAX_KEY ? fc_setting_by_key(key) : NULL;
    if (words > wire_remaining(r) / WORD_SIZE)
        wire_fail(r, FC_ERR_MALFORMED, "entry for key %u runs past the payload", key);
    else if (!spec)
        wire_fail(r, FC_ERR_INVALID_VALUE, "unknown setting key %u", key);
    else if (words != spec->count)
        wire_fail(r, FC_ERR_MALFORMED, "%s takes %u words, not %u", spec->name, spec->count, words);
    else if (*seen & ((uint64_t)1 << key))
        wire_fail(r, FC_ERR_MALFORMED, "%s appears twice", spec->name);
    else {
        *seen |= (uint64_t)1 << key;
        read_value(r, spec, s);
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
