/* render_brace.c — see render_brace.h. */
#include "render_brace.h"

#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

#define PATH_CAP 4096

bool fc_is_brace_pattern(const char *text)
{
    const char *at = strstr(text, "{}");
    return at && !strstr(at + 2, "{}");
}

/* `text[0..n)` with glob's special characters escaped, so that only the
 * "{}" turned "*" is a wildcard. False when it does not fit. */
static bool put_escaped(char *out, size_t *at, size_t size, const char *text, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (strchr("*?[]\\", text[i])) {
            if (*at + 1 >= size)
                return false;
            out[(*at)++] = '\\';
        }
        if (*at + 1 >= size)
            return false;
        out[(*at)++] = text[i];
    }
    out[*at] = '\0';
    return true;
}

/* The number where "{}" stands in a name glob found: all digits, at least one. */
static bool number_at(const char *name, size_t prefix_len, size_t suffix_len, uint32_t *out)
{
    size_t len = strlen(name);
    if (len <= prefix_len + suffix_len)
        return false;
    uint64_t n = 0;
    for (size_t i = prefix_len; i < len - suffix_len; i++) {
        if (name[i] < '0' || name[i] > '9')
            return false;
        n = n * 10 + (uint64_t)(name[i] - '0');
        if (n > UINT32_MAX)
            return false;
    }
    *out = (uint32_t)n;
    return true;
}

/* By number; names break ties, so that an error about two files of one
 * number names them in the same order every time. */
static int by_number(const void *a, const void *b)
{
    const fc_brace_match *x = a, *y = b;
    if (x->number != y->number)
        return (x->number > y->number) - (x->number < y->number);
    return strcmp(x->path, y->path);
}

/* The matches of glob's list that have digits where "{}" stands, sorted. */
static fc_code collect(const glob_t *g, size_t prefix_len, size_t suffix_len, fc_brace_match *m, size_t *count,
                       fc_error *err)
{
    *count = 0;
    for (size_t i = 0; i < g->gl_pathc; i++) {
        uint32_t number;
        if (!number_at(g->gl_pathv[i], prefix_len, suffix_len, &number))
            continue;
        m[*count].path = strdup(g->gl_pathv[i]);
        if (!m[*count].path)
            return fc_error_set(err, FC_ERR_NOMEM, "no memory for the list of frames");
        m[(*count)++].number = number;
    }
    qsort(m, *count, sizeof *m, by_number);
    return FC_OK;
}

static fc_code refuse_duplicates(const char *pattern, const fc_brace_match *m, size_t count, fc_error *err)
{
    for (size_t i = 1; i < count; i++)
        if (m[i].number == m[i - 1].number)
            return fc_error_set(err, FC_ERR_USAGE, "%s and %s are both frame %u of \"%s\"", m[i - 1].path,
                                m[i].path, (unsigned)m[i].number, pattern);
    return FC_OK;
}

fc_code fc_brace_matches(const char *pattern, fc_brace_match **out, size_t *count, fc_error *err)
{
    *out = NULL;
    *count = 0;
    const char *braces = strstr(pattern, "{}");
    size_t prefix_len = (size_t)(braces - pattern), suffix_len = strlen(braces + 2);
    char wildcard[2 * PATH_CAP + 2];
    size_t at = 0;
    if (!put_escaped(wildcard, &at, sizeof wildcard, pattern, prefix_len) || at + 1 >= sizeof wildcard)
        return fc_error_set(err, FC_ERR_USAGE, "the pattern \"%s\" is too long", pattern);
    wildcard[at++] = '*';
    if (!put_escaped(wildcard, &at, sizeof wildcard, braces + 2, suffix_len))
        return fc_error_set(err, FC_ERR_USAGE, "the pattern \"%s\" is too long", pattern);
    glob_t g;
    int rc = glob(wildcard, 0, NULL, &g);
    if (rc == GLOB_NOMATCH)
        return fc_error_set(err, FC_ERR_USAGE, "no file matches the pattern \"%s\"", pattern);
    if (rc != 0)
        return fc_error_set(err, FC_ERR_IO, "cannot list the files of \"%s\"", pattern);
    fc_brace_match *m = calloc(g.gl_pathc, sizeof *m);
    fc_code code = m ? collect(&g, prefix_len, suffix_len, m, count, err)
                     : fc_error_set(err, FC_ERR_NOMEM, "no memory for the list of frames");
    globfree(&g);
    if (code == FC_OK && *count == 0)
        code = fc_error_set(err, FC_ERR_USAGE, "no file matches the pattern \"%s\" (digits where {} is)", pattern);
    if (code == FC_OK)
        code = refuse_duplicates(pattern, m, *count, err);
    if (code != FC_OK) {
        fc_brace_matches_free(m, *count);
        *count = 0;
        return code;
    }
    *out = m;
    return FC_OK;
}

void fc_brace_matches_free(fc_brace_match *matches, size_t count)
{
    for (size_t i = 0; i < count && matches; i++)
        free(matches[i].path);
    free(matches);
}
