/* reader_select.c — --select: parsing "ATTR<op>V[,V...]" and keeping the
 * particles of a read frame for which every selection holds, over the frame's
 * attributes and the named scalars the reader kept (reader_extras.h). */
#include "reader_select.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"

/* ---- parsing ---- */

static const struct {
    const char *text;
    fc_select_op op;
} operators[] = { /* two-character ones first */
    { "<=", FC_SELECT_LE }, { ">=", FC_SELECT_GE }, { "!=", FC_SELECT_NOT_IN }, { "==", FC_SELECT_IN },
    { "<", FC_SELECT_LT },  { ">", FC_SELECT_GT },  { "=", FC_SELECT_IN },
};

static fc_code bad_select(const char *text, fc_error *err, const char *why)
{
    return fc_error_set(err, FC_ERR_USAGE, "--select '%s': %s (ATTR=V[,V...], ATTR!=V[,V...], ATTR<V, ATTR<=V, "
                        "ATTR>V or ATTR>=V)", text, why);
}

/* Comma-separated numbers; one only for the comparisons. */
static fc_code parse_values(const char *text, const char *at, fc_select *out, fc_error *err)
{
    bool list = out->op == FC_SELECT_IN || out->op == FC_SELECT_NOT_IN;
    for (;;) {
        char *end = NULL;
        double value = strtod(at, &end);
        if (end == at || !isfinite(value))
            return bad_select(text, err, "expected a number after the operator");
        if (out->value_count == FC_SELECT_MAX_VALUES)
            return bad_select(text, err, "more than 16 values");
        out->values[out->value_count++] = value;
        while (*end == ' ')
            end++;
        if (*end == '\0')
            return FC_OK;
        if (*end != ',' || !list)
            return bad_select(text, err, list ? "expected ',' between values" : "one value after <, <=, > or >=");
        at = end + 1;
    }
}

fc_code fc_select_parse(const char *text, fc_select *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    if (strlen(text) >= sizeof out->text)
        return fc_error_set(err, FC_ERR_USAGE, "--select '%.40s...': longer than %d characters", text,
                            FC_SELECT_TEXT_MAX - 1);
    snprintf(out->text, sizeof out->text, "%s", text);
    size_t name_len = strcspn(text, "<>!=");
    const char *at = text + name_len;
    size_t k = 0;
    while (k < sizeof operators / sizeof operators[0] && strncmp(at, operators[k].text, strlen(operators[k].text)))
        k++;
    if (*at == '\0' || k == sizeof operators / sizeof operators[0])
        return bad_select(text, err, "no operator");
    while (name_len > 0 && text[name_len - 1] == ' ')
        name_len--;
    size_t skip = strspn(text, " ");
    if (name_len <= skip || name_len - skip >= sizeof out->attribute)
        return bad_select(text, err, "expected an attribute name before the operator");
    memcpy(out->attribute, text + skip, name_len - skip);
    out->op = operators[k].op;
    return parse_values(text, at + strlen(operators[k].text), out, err);
}

/* ---- one attribute's values ---- */

typedef struct select_source {
    const float *floats;     /* value i = floats[stride i + offset] + shift */
    size_t stride, offset;
    double shift;            /* positions: the recentring's offset along the axis */
    bool speed;              /* |velocity i| */
    const uint32_t *ids;
    const double *doubles;
} select_source;

static double source_value(const select_source *s, uint64_t i)
{
    if (s->ids)
        return s->ids[i];
    if (s->doubles)
        return s->doubles[i];
    const float *v = s->floats + s->stride * i;
    if (s->speed)
        return sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    return (double)v[s->offset] + s->shift;
}

/* The frame's own attributes, by the names --color-by and the readers use. */
static bool frame_source(const fc_frame *f, const char *name, const double shift[3], select_source *s)
{
    static const char *const axes[] = { "x", "y", "z" }, *const speeds[] = { "vx", "vy", "vz" };
    memset(s, 0, sizeof *s);
    fc_span n = { name, strlen(name) };
    for (size_t k = 0; k < 3; k++) {
        if (fc_span_iequals(n, axes[k]))
            return *s = (select_source){ .floats = f->positions, .stride = 3, .offset = k, .shift = shift[k] }, true;
        if (f->velocity && fc_span_iequals(n, speeds[k]))
            return *s = (select_source){ .floats = f->velocity, .stride = 3, .offset = k }, true;
    }
    if (f->velocity && fc_span_iequals(n, "speed"))
        return *s = (select_source){ .floats = f->velocity, .stride = 3, .speed = true }, true;
    if (f->density && fc_span_iequals(n, "density"))
        return *s = (select_source){ .floats = f->density, .stride = 1 }, true;
    if (f->radius && fc_span_iequals(n, "radius"))
        return *s = (select_source){ .floats = f->radius, .stride = 1 }, true;
    if (f->ids && fc_span_iequals(n, "id"))
        return *s = (select_source){ .ids = f->ids }, true;
    return false;
}

/* "x, y, z, density, ..., Type, Mk": what a selection may name in this file. */
static void list_attributes(const fc_frame *f, const fc_read_extras *x, char *out, size_t size)
{
    snprintf(out, size, "x, y, z%s%s%s%s", f->density ? ", density" : "", f->velocity ? ", vx, vy, vz, speed" : "",
             f->ids ? ", id" : "", f->radius ? ", radius" : "");
    for (size_t i = 0; x && i < x->size; i++) {
        size_t used = strlen(out);
        snprintf(out + used, size - used, ", %s", x->names[i]);
    }
}

static bool holds(const fc_select *sel, double v)
{
    bool equal = false;
    for (uint32_t k = 0; k < sel->value_count; k++)
        equal = equal || v == sel->values[k];
    switch (sel->op) {
    case FC_SELECT_IN:
        return equal;
    case FC_SELECT_NOT_IN:
        return !equal && !isnan(v);
    case FC_SELECT_LT:
        return v < sel->values[0];
    case FC_SELECT_LE:
        return v <= sel->values[0];
    case FC_SELECT_GT:
        return v > sel->values[0];
    case FC_SELECT_GE:
        return v >= sel->values[0];
    }
    return false;
}

/* ---- keeping particles ---- */

static void compact_floats(float *a, size_t stride, const uint8_t *keep, uint64_t count)
{
    uint64_t w = 0;
    for (uint64_t i = 0; a && i < count; i++)
        if (keep[i])
            memmove(a + stride * w++, a + stride * i, stride * sizeof *a);
}

static void compact(fc_frame *f, fc_read_extras *x, const uint8_t *keep, uint64_t kept)
{
    compact_floats(f->positions, 3, keep, f->count);
    compact_floats(f->density, 1, keep, f->count);
    compact_floats(f->velocity, 3, keep, f->count);
    compact_floats(f->radius, 1, keep, f->count);
    uint64_t w = 0;
    for (uint64_t i = 0; f->ids && i < f->count; i++)
        if (keep[i])
            f->ids[w++] = f->ids[i];
    for (size_t k = 0; x && k < x->size; k++) {
        w = 0;
        for (uint64_t i = 0; i < f->count; i++)
            if (keep[i])
                x->values[k][w++] = x->values[k][i];
    }
    f->count = kept;
}

static fc_code apply_one(fc_frame *f, fc_read_extras *x, const fc_select *sel, const double offset[3], uint8_t *keep,
                         const char *name, fc_error *err)
{
    select_source s;
    if (!frame_source(f, sel->attribute, offset, &s)) {
        memset(&s, 0, sizeof s);
        s.doubles = x ? fc_extras_find(x, sel->attribute) : NULL;
    }
    if (s.floats == NULL && s.ids == NULL && s.doubles == NULL) {
        char available[1024];
        list_attributes(f, x, available, sizeof available);
        return fc_error_set(err, FC_ERR_USAGE, "%s: --select '%s': no attribute '%s' (this file has: %s)", name,
                            sel->text, sel->attribute, available);
    }
    uint64_t kept = 0;
    for (uint64_t i = 0; i < f->count; i++) {
        keep[i] = holds(sel, source_value(&s, i));
        kept += keep[i];
    }
    if (kept == 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s: --select '%s' keeps none of the %llu particles", name, sel->text,
                            (unsigned long long)f->count);
    compact(f, x, keep, kept);
    return FC_OK;
}

fc_code fc_select_apply(fc_frame *frame, fc_read_extras *extras, const fc_read_options *o, const double offset[3],
                        const char *name, fc_error *err)
{
    if (o == NULL || o->select_count == 0)
        return FC_OK;
    uint8_t *keep = malloc((size_t)frame->count);
    if (keep == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: no memory to select among %llu particles", name,
                            (unsigned long long)frame->count);
    fc_code code = FC_OK;
    for (uint32_t k = 0; k < o->select_count && k < FC_SELECT_MAX && code == FC_OK; k++)
        code = apply_one(frame, extras, &o->select[k], offset, keep, name, err);
    free(keep);
    return code;
}
