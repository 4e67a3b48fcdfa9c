/* cli_setting_options.c — see cli_setting_options.h. */
#include "cli_setting_options.h"

#include <float.h>
#include <string.h>

#include "cli_values.h"
#include "fc_options.h"
#include "fc_error.h"

/* At most this many settings: keys are bits of a u64 (wire_settings.c, fc_cli_settings.given). */
#define SETTINGS_MAX 64
/* Enough for any setting's values as written on the command line (three floats). */
#define VALUE_TEXT_MAX 256

void fc_cli_settings_init(fc_cli_settings *s)
{
    fc_settings_default(&s->values);
    s->given = 0;
}

static uint64_t key_bit(const fc_setting_spec *spec)
{
    return (uint64_t)1 << spec->key;
}

bool fc_cli_setting_given(const fc_cli_settings *s, const char *name)
{
    const fc_setting_spec *spec = fc_setting_by_name(name);
    return spec && (s->given & key_bit(spec));
}

/* "R,G,B" or "MIN:MAX" into spec->count floats. */
static fc_code parse_floats(const fc_setting_spec *spec, const char *value, float *out, fc_error *err)
{
    char text[VALUE_TEXT_MAX];
    if (strlen(value) >= sizeof text)
        return fc_error_set(err, FC_ERR_USAGE, "%s needs %s, not a %zu-byte value", spec->option,
                            spec->metavar, strlen(value));
    strcpy(text, value);
    char *part = text;
    for (uint32_t i = 0; i < spec->count; i++) {
        bool last = i + 1 == spec->count;
        char *end = last ? part + strlen(part) : strchr(part, spec->separator);
        if (!end || (last && spec->separator && strchr(part, spec->separator)))
            return fc_error_set(err, FC_ERR_USAGE, "%s needs %s, not \"%s\"", spec->option, spec->metavar, value);
        *end = '\0';
        fc_code code = fc_cli_parse_float(spec->option, part, &out[i], err);
        if (code != FC_OK)
            return code;
        part = end + 1;
    }
    return FC_OK;
}

/* The command line's own rules beyond the setting's domain. */
static fc_code check_cli_rules(const fc_setting_spec *spec, const float *v, const char *value, fc_error *err)
{
    /* 0 means "from the particles" on the wire; on the command line that is leaving the option out. */
    if ((spec->flags & FC_SETTING_CLI_POSITIVE) && !(v[0] > 0.0f))
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a value > 0, not %s", spec->option, value);
    if ((spec->flags & FC_SETTING_RANGE) && !(v[0] < v[1]))
        return fc_error_set(err, FC_ERR_USAGE, "%s needs MIN below MAX, not \"%s\"", spec->option, value);
    return FC_OK;
}

static fc_code parse_value(const fc_setting_spec *spec, const char *value, fc_settings *into, fc_error *err)
{
    void *field = fc_setting_field(spec, into);
    switch (spec->type) {
    case FC_SETTING_FLOAT:
    case FC_SETTING_SCALE: {
        fc_code code = parse_floats(spec, value, field, err);
        return code != FC_OK ? code : check_cli_rules(spec, field, value, err);
    }
    case FC_SETTING_UINT: return fc_cli_parse_uint(spec->option, value, 0, UINT32_MAX, field, err);
    case FC_SETTING_CHOICE: {
        int index;
        fc_code code = fc_cli_parse_choice(spec->option, value, spec->choices, &index, err);
        if (code == FC_OK)
            *(uint32_t *)field = (uint32_t)index;
        return code;
    }
    }
    return fc_error_set(err, FC_ERR_USAGE, "%s has an unknown type", spec->option);
}

/* Settings whose default follows the smoothing method take the new method's. */
static void follow_smoothing(fc_cli_settings *s)
{
    size_t count;
    const fc_setting_spec *table = fc_settings_table(&count);
    for (size_t i = 0; i < count; i++)
        if ((table[i].flags & FC_SETTING_PER_SMOOTHING) && !(s->given & key_bit(&table[i])))
            *(uint32_t *)fc_setting_field(&table[i], &s->values) =
                fc_smoothing_default_iterations(s->values.smoothing);
}

fc_code fc_cli_set_setting(fc_cli_settings *s, const fc_setting_spec *spec, const char *value, fc_error *err)
{
    /* Parsed into a copy, so a refused value leaves the settings as they were. */
    fc_settings next = s->values;
    fc_code code = parse_value(spec, value, &next, err);
    if (code != FC_OK)
        return code;
    fc_error why;
    if (fc_setting_validate(spec, &next, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "%s: %s", spec->option, why.message);
    s->values = next;
    s->given |= key_bit(spec);
    follow_smoothing(s);
    return FC_OK;
}

/* An fc_option setter: `target` is the fc_cli_settings, `name` the setting's option. */
static fc_code set_from_option(void *target, const char *name, const char *value, fc_error *err)
{
    return fc_cli_set_setting(target, fc_setting_by_option(name), value, err);
}

fc_code fc_cli_take_setting(fc_cli_settings *s, int argc, char **argv, int *i, bool *known, fc_error *err)
{
    size_t count;
    const fc_setting_spec *table = fc_settings_table(&count);
    fc_option rows[SETTINGS_MAX];
    size_t listed = 0;
    for (size_t k = 0; k < count && listed < SETTINGS_MAX; k++)
        if (table[k].option)
            rows[listed++] = (fc_option){table[k].option, "VALUE", set_from_option, NULL, NULL};
    const fc_option_table options = {"fluidcast", rows, listed, NULL, NULL};
    return fc_options_take(&options, argc, argv, i, s, known, err);
}

/* ---- help ---- */

static const char *const group_titles[FC_GROUP_COUNT] = {
    [FC_GROUP_SURFACE] = "fluid surface",
    [FC_GROUP_SHADING] = "shading",
    [FC_GROUP_COLORING] = "colour by attribute",
    [FC_GROUP_IMAGE] = "image",
};

/* The value as the help names it: "sphere|anisotropic", "N". */
static void usage_text(const fc_setting_spec *spec, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    if (spec->type != FC_SETTING_CHOICE) {
        snprintf(out + used, size - used, "%s", spec->metavar);
        return;
    }
    for (uint32_t i = 0; spec->choices[i] && used < size; i++)
        used += (size_t)snprintf(out + used, size - used, "%s%s", i ? "|" : "", spec->choices[i]);
}

/* What values the option takes, as the help says it: "1..3", "each 0..1", "> 0". */
static void domain_text(const fc_setting_spec *spec, char *out, size_t size)
{
    bool min_open = spec->flags & FC_SETTING_MIN_OPEN, max_open = spec->flags & FC_SETTING_MAX_OPEN;
    const char *each = spec->count == 3 ? "each " : "";
    out[0] = '\0';
    if (spec->type == FC_SETTING_SCALE)
        snprintf(out, size, "1, 0.5 or 0.25");
    else if (spec->type == FC_SETTING_CHOICE || spec->min <= -FLT_MAX)
        return;
    else if (spec->flags & FC_SETTING_CLI_POSITIVE)
        snprintf(out, size, "> 0");
    else if (spec->max >= FLT_MAX)
        snprintf(out, size, "%s%s %g", each, min_open ? ">" : ">=", spec->min);
    else if (min_open || max_open)
        snprintf(out, size, "%s%g %s %s %s %g", each, spec->min, min_open ? "<" : "<=", spec->metavar,
                 max_open ? "<" : "<=", spec->max);
    else
        snprintf(out, size, "%s%g..%g", each, spec->min, spec->max);
}

/* The name of smoothing method m, NULL past the last. */
static const char *smoothing_choice(uint32_t m)
{
    return fc_setting_by_name("smoothing")->choices[m];
}

/* "default 1.33", "default: curvature 60, ..."; empty where the
 * command line chooses the value from the particles (the help says how). */
static void default_text(const fc_setting_spec *spec, const fc_settings *d, char *out, size_t size)
{
    const void *field = fc_setting_field_const(spec, d);
    size_t used = 0;
    out[0] = '\0';
    if (spec->flags & FC_SETTING_FROM_FRAME)
        return;
    if (spec->flags & FC_SETTING_PER_SMOOTHING) {
        used = (size_t)snprintf(out, size, "default:");
        for (uint32_t m = 0; smoothing_choice(m) && used < size; m++)
            if (fc_smoothing_default_iterations((fc_smoothing)m) > 0)
                used += (size_t)snprintf(out + used, size - used, "%s %s %u", used > 8 ? "," : "",
                                         smoothing_choice(m), fc_smoothing_default_iterations((fc_smoothing)m));
        return;
    }
    used = (size_t)snprintf(out, size, "default ");
    for (uint32_t i = 0; i < spec->count && used < size; i++) {
        const char *sep = i ? (char[]){spec->separator, '\0'} : "";
        if (spec->type == FC_SETTING_FLOAT || spec->type == FC_SETTING_SCALE)
            used += (size_t)snprintf(out + used, size - used, "%s%g", sep, (double)((const float *)field)[i]);
        else if (spec->type == FC_SETTING_UINT)
            used += (size_t)snprintf(out + used, size - used, "%u", *(const uint32_t *)field);
        else
            used += (size_t)snprintf(out + used, size - used, "%s", spec->choices[*(const uint32_t *)field]);
    }
}

static void print_setting(FILE *to, const fc_setting_spec *spec, const fc_settings *d)
{
    char usage[128], domain[64], def[128], text[1024];
    usage_text(spec, usage, sizeof usage);
    domain_text(spec, domain, sizeof domain);
    default_text(spec, d, def, sizeof def);
    /* "index of refraction (1..3; default 1.33)" */
    if (domain[0] || def[0])
        snprintf(text, sizeof text, "%s (%s%s%s)", spec->help, domain, domain[0] && def[0] ? "; " : "", def);
    else
        snprintf(text, sizeof text, "%s", spec->help);
    fc_options_print_option(to, &(fc_option){spec->option, usage, NULL, text, NULL});
}

void fc_cli_print_settings_help(FILE *to, const fc_settings *defaults)
{
    size_t count;
    const fc_setting_spec *table = fc_settings_table(&count);
    for (int group = 0; group < FC_GROUP_COUNT; group++) {
        fprintf(to, "%s:\n", group_titles[group]);
        for (size_t i = 0; i < count; i++)
            if ((int)table[i].group == group && table[i].option)
                print_setting(to, &table[i], defaults);
        fputc('\n', to);
    }
}
