/* flat_constants.c — see flat_constants.h. */
#include "flat_constants.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

/* The types that can travel as flat inputs: base type, components per
 * location, locations. */
typedef struct value_type {
    const char *name;
    char base;   /* 'f', 'i', 'u': components of different bases never share a location */
    int components;
    int locations;
} value_type;

static const value_type value_types[] = {
    {"float", 'f', 1, 1}, {"vec2", 'f', 2, 1}, {"vec3", 'f', 3, 1}, {"vec4", 'f', 4, 1},
    {"int", 'i', 1, 1},   {"ivec2", 'i', 2, 1}, {"ivec3", 'i', 3, 1}, {"ivec4", 'i', 4, 1},
    {"uint", 'u', 1, 1},  {"uvec2", 'u', 2, 1}, {"uvec3", 'u', 3, 1}, {"uvec4", 'u', 4, 1},
    {"mat3", 'f', 3, 3},  {"mat4", 'f', 4, 4},
};

static const value_type *find_type(const char *name)
{
    for (size_t i = 0; i < sizeof value_types / sizeof value_types[0]; i++)
        if (strcmp(value_types[i].name, name) == 0)
            return &value_types[i];
    return NULL;
}

/* One parsed declaration: where in the line the statement ends (after ';'). */
typedef struct declaration {
    int location;
    char type[8];
    char name[FC_FLAT_NAME_MAX];
    const char *rest;
} declaration;

static const char *skip_spaces(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    return p;
}

static bool take(const char **p, const char *end, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(end - *p) < n || strncmp(*p, word, n) != 0)
        return false;
    *p += n;
    return true;
}

/* An identifier into out (at most size - 1 characters); false when none or too long. */
static bool take_identifier(const char **p, const char *end, char *out, size_t size)
{
    size_t n = 0;
    while (*p + n < end && (isalnum((unsigned char)(*p)[n]) || (*p)[n] == '_'))
        n++;
    if (n == 0 || n >= size)
        return false;
    memcpy(out, *p, n);
    out[n] = '\0';
    *p += n;
    return true;
}

/* Whether [line, end) is `layout(location = N) uniform TYPE NAME;` with TYPE a value type. */
static bool parse_declaration(const char *line, const char *end, declaration *d)
{
    const char *p = skip_spaces(line, end);
    if (!take(&p, end, "layout(location = "))
        return false;
    char *after = NULL;
    long location = strtol(p, &after, 10);
    if (after == p || after > end || location < 0 || location > 1023)
        return false;
    p = after;
    if (!take(&p, end, ") uniform "))
        return false;
    p = skip_spaces(p, end);
    if (!take_identifier(&p, end, d->type, sizeof d->type) || !find_type(d->type))
        return false;
    p = skip_spaces(p, end);
    if (!take_identifier(&p, end, d->name, sizeof d->name))
        return false;
    p = skip_spaces(p, end);
    if (!take(&p, end, ";"))   /* arrays ("name[4];") and initialisers stay uniforms */
        return false;
    d->location = (int)location;
    d->rest = p;
    return true;
}

/* Whether the line declares a shader input: [layout(...)] [qualifiers] in TYPE ... */
static bool declares_input(const char *line, const char *end)
{
    const char *p = skip_spaces(line, end);
    if (take(&p, end, "layout(")) {
        while (p < end && *p != ')')
            p++;
        if (p == end)
            return false;
        p = skip_spaces(p + 1, end);
    }
    static const char *const qualifiers[] = {"flat ", "noperspective ", "smooth ", "centroid "};
    for (bool again = true; again;) {
        again = false;
        for (size_t i = 0; i < sizeof qualifiers / sizeof qualifiers[0]; i++)
            if (take(&p, end, qualifiers[i])) {
                p = skip_spaces(p, end);
                again = true;
            }
    }
    return take(&p, end, "in ");
}

static const char *line_end(const char *p)
{
    const char *e = strchr(p, '\n');
    return e ? e : p + strlen(p);
}

static fc_flat_constant *find_constant(fc_flat_constants *c, const char *name)
{
    for (size_t i = 0; i < c->count; i++)
        if (strcmp(c->items[i].name, name) == 0)
            return &c->items[i];
    return NULL;
}

static fc_code add(fc_flat_constants *c, const declaration *d, const char *file, fc_error *err)
{
    fc_flat_constant *seen = find_constant(c, d->name);
    if (seen) {
        if (seen->location != d->location || strcmp(seen->type, d->type) != 0)
            return fc_error_set(err, FC_ERR_GL, "%s: uniform %s declared again as %s at location %d (was %s at %d)",
                                file, d->name, d->type, d->location, seen->type, seen->location);
        return FC_OK;
    }
    if (c->count == FC_FLAT_CONSTANTS_MAX)
        return fc_error_set(err, FC_ERR_GL, "%s: more than %d uniforms to pass as flat inputs", file,
                            FC_FLAT_CONSTANTS_MAX);
    fc_flat_constant *k = &c->items[c->count++];
    *k = (fc_flat_constant){.location = d->location, .slot = -1, .component = -1};
    snprintf(k->type, sizeof k->type, "%s", d->type);
    snprintf(k->name, sizeof k->name, "%s", d->name);
    return FC_OK;
}

fc_code fc_flat_constants_collect(fc_flat_constants *c, const char *source, const char *file, fc_error *err)
{
    for (const char *line = source; *line;) {
        const char *end = line_end(line);
        declaration d;
        if (declares_input(line, end))
            return fc_error_set(err, FC_ERR_GL, "%s: flat constants need a fragment stage without inputs", file);
        if (parse_declaration(line, end, &d)) {
            fc_code code = add(c, &d, file, err);
            if (code != FC_OK)
                return code;
        }
        line = *end ? end + 1 : end;
    }
    return FC_OK;
}

/* First fit: a location of the same base type with room after its last
 * component, else a new one. Matrices take whole new locations. */
void fc_flat_constants_assign(fc_flat_constants *c, int max_slots)
{
    enum { SLOTS_MAX = 64 };
    int used[SLOTS_MAX] = {0};
    char base[SLOTS_MAX] = {0};
    if (max_slots > SLOTS_MAX)
        max_slots = SLOTS_MAX;
    c->slots_used = 0;
    for (size_t i = 0; i < c->count; i++) {
        fc_flat_constant *k = &c->items[i];
        const value_type *t = find_type(k->type);
        k->slot = k->component = -1;
        if (t->locations > 1) {
            if (c->slots_used + t->locations <= max_slots) {
                k->slot = c->slots_used;
                for (int s = 0; s < t->locations; s++) {
                    used[c->slots_used] = 4;
                    base[c->slots_used++] = t->base;
                }
            }
            continue;
        }
        for (int s = 0; s < c->slots_used && k->slot < 0; s++)
            if (base[s] == t->base && used[s] + t->components <= 4) {
                k->slot = s;
                k->component = used[s];
                used[s] += t->components;
            }
        if (k->slot < 0 && c->slots_used < max_slots) {
            k->slot = c->slots_used;
            k->component = 0;
            used[c->slots_used] = t->components;
            base[c->slots_used++] = t->base;
        }
    }
}

/* A growing text buffer; `failed` once an allocation fails. */
typedef struct text {
    char *data;
    size_t length, capacity;
    bool failed;
} text;

static void append(text *t, const char *s, size_t n)
{
    if (t->failed)
        return;
    if (t->length + n + 1 > t->capacity) {
        size_t capacity = 2 * (t->length + n + 1) + 256;
        char *grown = realloc(t->data, capacity);
        if (!grown) {
            t->failed = true;
            return;
        }
        t->data = grown;
        t->capacity = capacity;
    }
    memcpy(t->data + t->length, s, n);
    t->length += n;
    t->data[t->length] = '\0';
}

static void appendf(text *t, const char *format, ...)
{
    char line[256];
    va_list args;
    va_start(args, format);
    int n = vsnprintf(line, sizeof line, format, args);
    va_end(args);
    if (n < 0 || (size_t)n >= sizeof line) {
        t->failed = true;
        return;
    }
    append(t, line, (size_t)n);
}

static fc_code finish(text *t, char **out, fc_error *err)
{
    append(t, "", 0);
    if (t->failed) {
        free(t->data);
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory writing a shader's flat constants");
    }
    *out = t->data;
    return FC_OK;
}

/* The layout qualifier of the input or output of k. */
static void append_layout(text *t, const fc_flat_constant *k)
{
    if (k->component >= 0)
        appendf(t, "layout(location = %d, component = %d) flat", k->slot, k->component);
    else
        appendf(t, "layout(location = %d) flat", k->slot);
}

fc_code fc_flat_constants_rewrite(const fc_flat_constants *c, const char *source, char **out, fc_error *err)
{
    text t = {0};
    for (const char *line = source; *line;) {
        const char *end = line_end(line);
        declaration d;
        const fc_flat_constant *k = NULL;
        if (parse_declaration(line, end, &d))
            k = find_constant((fc_flat_constants *)c, d.name);
        if (k && k->slot >= 0) {
            append_layout(&t, k);
            appendf(&t, " in %s %s;", k->type, k->name);
            append(&t, d.rest, (size_t)(end - d.rest));
        } else {
            append(&t, line, (size_t)(end - line));
        }
        if (*end)
            append(&t, "\n", 1);
        line = *end ? end + 1 : end;
    }
    return finish(&t, out, err);
}

fc_code fc_flat_constants_vertex_source(const fc_flat_constants *c, char **out, fc_error *err)
{
    text t = {0};
    appendf(&t, "#version 450 core\n");
    appendf(&t, "// Generated by flat_constants.c: the fragment stage's uniforms as flat outputs.\n");
    for (size_t i = 0; i < c->count; i++) {
        const fc_flat_constant *k = &c->items[i];
        if (k->slot < 0)
            continue;
        appendf(&t, "layout(location = %d) uniform %s %s;\n", k->location, k->type, k->name);
        append_layout(&t, k);
        appendf(&t, " out %s fc_flat_%s;\n", k->type, k->name);
    }
    appendf(&t, "\nvoid fc_forward_constants()\n{\n");
    for (size_t i = 0; i < c->count; i++)
        if (c->items[i].slot >= 0)
            appendf(&t, "    fc_flat_%s = %s;\n", c->items[i].name, c->items[i].name);
    appendf(&t, "}\n");
    return finish(&t, out, err);
}
