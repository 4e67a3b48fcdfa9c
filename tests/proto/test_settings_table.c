/* test_settings_table.c — the settings' table (fc_settings.h) walked entry by
 * entry: it covers every byte of fc_settings once, names each setting by a
 * distinct key, name and option, its defaults are fc_settings_default's and
 * valid, and for every entry a value inside its domain survives the SETTINGS
 * codec while one just outside is refused by validation and on the wire,
 * naming the setting. A new entry is checked here without a new line. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "fc_settings.h"
#include "test_util.h"
#include "wire.h"

static const fc_setting_spec *table_of(size_t *count)
{
    const fc_setting_spec *table = fc_settings_table(count);
    CHECK(table != NULL && *count > 0);
    return table;
}

/* Every byte of fc_settings belongs to exactly one entry. */
static void test_table_covers_the_struct(void)
{
    size_t count;
    const fc_setting_spec *table = table_of(&count);
    unsigned char owner[sizeof(fc_settings)] = {0};
    for (size_t i = 0; i < count; i++) {
        CHECK_MSG(table[i].count >= 1 && table[i].count <= 3, "%s: %u values", table[i].name, table[i].count);
        for (size_t b = table[i].offset; b < table[i].offset + 4 * table[i].count; b++) {
            CHECK_MSG(b < sizeof owner && owner[b] == 0, "%s overlaps byte %zu", table[i].name, b);
            if (b < sizeof owner)
                owner[b] = 1;
        }
    }
    for (size_t b = 0; b < sizeof owner; b++)
        CHECK_MSG(owner[b] == 1, "byte %zu of fc_settings is in no entry", b);
}

static void test_names_keys_and_options_are_distinct(void)
{
    size_t count;
    const fc_setting_spec *table = table_of(&count);
    for (size_t i = 0; i < count; i++) {
        const fc_setting_spec *s = &table[i];
        CHECK_MSG(s->key >= 1 && s->key < 64, "%s: key %u", s->name, s->key);
        CHECK_MSG(i == 0 || s->key > table[i - 1].key, "%s: keys out of order", s->name);
        CHECK(fc_setting_by_key(s->key) == s && fc_setting_by_name(s->name) == s);
        CHECK_MSG(s->option && strncmp(s->option, "--", 2) == 0 && fc_setting_by_option(s->option) == s,
                  "%s: option", s->name);
        CHECK_MSG(s->help && s->help[0], "%s: no help", s->name);
        CHECK_MSG(s->type == FC_SETTING_CHOICE ? fc_setting_choice_count(s) >= 2 : s->metavar != NULL,
                  "%s: choices or metavar", s->name);
        CHECK_MSG(s->count == 1 || s->separator, "%s: several values without a separator", s->name);
        CHECK((int)s->group >= 0 && s->group < FC_GROUP_COUNT);
    }
    CHECK(fc_setting_by_key(25) == NULL && fc_setting_by_name("nope") == NULL && fc_setting_by_option("--nope") == NULL);
}

/* A value of the entry's domain other than its default (the far end of the
 * domain, a choice's last name), and the values just outside it (*n_outside:
 * none for a domain of every finite float). */
static void inside_and_outside(const fc_setting_spec *s, float *inside, float outside[2], int *n_outside)
{
    *n_outside = 0;
    switch (s->type) {
    case FC_SETTING_SCALE:
        *inside = s->initial[0] == 0.25f ? 1.0f : 0.25f;
        outside[(*n_outside)++] = 0.75f;
        outside[(*n_outside)++] = 2.0f;
        return;
    case FC_SETTING_CHOICE: {
        uint32_t last = fc_setting_choice_count(s) - 1;
        *inside = (float)(last == (uint32_t)s->initial[0] ? 0 : last);
        outside[(*n_outside)++] = (float)(last + 1);
        return;
    }
    case FC_SETTING_UINT:
        *inside = (float)s->max;
        outside[(*n_outside)++] = (float)s->max + 1.0f;
        return;
    case FC_SETTING_FLOAT:
        *inside = s->max >= FLT_MAX ? (float)s->min + 7.0f : (float)s->max - (s->flags & FC_SETTING_MAX_OPEN ? 0.5f : 0.0f);
        if (s->min > -FLT_MAX)
            outside[(*n_outside)++] = s->flags & FC_SETTING_MIN_OPEN ? (float)s->min : nextafterf((float)s->min, -INFINITY);
        if (s->max < FLT_MAX)
            outside[(*n_outside)++] = s->flags & FC_SETTING_MAX_OPEN ? (float)s->max : nextafterf((float)s->max, INFINITY);
        else
            outside[(*n_outside)++] = INFINITY;
        return;
    }
}

static void store(const fc_setting_spec *s, fc_settings *into, float v)
{
    void *field = fc_setting_field(s, into);
    for (uint32_t c = 0; c < s->count; c++) {
        if (s->type == FC_SETTING_FLOAT || s->type == FC_SETTING_SCALE)
            ((float *)field)[c] = v;
        else
            ((uint32_t *)field)[c] = (uint32_t)v;
    }
}

static fc_code read_back(const fc_settings *sent, fc_settings *received, fc_error *err)
{
    fc_buf buf;
    fc_buf_init(&buf);
    CHECK_CODE(fc_wire_write_settings(&buf, 1, sent, err), FC_OK);
    fc_settings_default(received);
    fc_code code = fc_wire_read_settings(buf.data + FC_WIRE_HEADER_SIZE, buf.len - FC_WIRE_HEADER_SIZE, received, err);
    fc_buf_free(&buf);
    return code;
}

static void test_each_entry_round_trips_and_refuses(void)
{
    size_t count;
    const fc_setting_spec *table = table_of(&count);
    fc_settings defaults;
    fc_settings_default(&defaults);
    fc_error err;
    CHECK_CODE(fc_settings_validate(&defaults, &err), FC_OK);
    for (size_t i = 0; i < count; i++) {
        const fc_setting_spec *s = &table[i];
        const void *field = fc_setting_field_const(s, &defaults);
        for (uint32_t c = 0; c < s->count; c++) {
            bool f = s->type == FC_SETTING_FLOAT || s->type == FC_SETTING_SCALE;
            float v = f ? ((const float *)field)[c] : (float)((const uint32_t *)field)[c];
            CHECK_MSG(v == s->initial[c], "%s[%u]: default %g, table %g", s->name, c, (double)v, (double)s->initial[c]);
        }
        float inside = 0.0f, outside[2];
        int n_outside;
        inside_and_outside(s, &inside, outside, &n_outside);
        fc_settings sent = defaults, received;
        store(s, &sent, inside);
        if (s->flags & FC_SETTING_RANGE)   /* a range's ends in order */
            ((float *)fc_setting_field(s, &sent))[0] = -1.0f;
        CHECK_MSG(read_back(&sent, &received, &err) == FC_OK, "%s: %s", s->name, err.message);
        CHECK_MSG(memcmp(&sent, &received, sizeof sent) == 0, "%s: not received as sent", s->name);
        for (int k = 0; k < n_outside; k++) {
            sent = defaults;
            store(s, &sent, outside[k]);
            CHECK_MSG(fc_setting_validate(s, &sent, &err) == FC_ERR_INVALID_VALUE && strstr(err.message, s->name),
                      "%s: %g accepted", s->name, (double)outside[k]);
            CHECK_MSG(read_back(&sent, &received, &err) == FC_ERR_INVALID_VALUE && strstr(err.message, s->name),
                      "%s: %g accepted on the wire", s->name, (double)outside[k]);
        }
    }
}

int main(void)
{
    test_table_covers_the_struct();
    test_names_keys_and_options_are_distinct();
    test_each_entry_round_trips_and_refuses();
    return test_result();
}
