/* render_inputs.c — see render_inputs.h. */
#define _GNU_SOURCE   /* strverscmp */
#include "render_inputs.h"

#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "render_brace.h"

#define MAX_FRAMES 1000000u
#define PATH_CAP 4096

/* ---- patterns ---- */

typedef struct conversion {
    size_t at, length;   /* where the %...d is in the pattern, and its length */
    int width;
    bool zero_pad;
} conversion;

/* Finds the one %d conversion; false when there is none, more than one, or another % form. */
static bool find_conversion(const char *text, conversion *c)
{
    int found = 0;
    for (size_t i = 0; text[i]; i++) {
        if (text[i] != '%')
            continue;
        if (text[i + 1] == '%') {
            i++;
            continue;
        }
        size_t j = i + 1;
        bool zero = text[j] == '0';
        int width = 0;
        while (text[j] >= '0' && text[j] <= '9' && width < 100)
            width = width * 10 + (text[j++] - '0');
        if (text[j] != 'd')
            return false;
        *c = (conversion){.at = i, .length = j + 1 - i, .width = width, .zero_pad = zero};
        found++;
        i = j;
    }
    return found == 1;
}

bool fc_is_frame_pattern(const char *text)
{
    conversion c;
    return find_conversion(text, &c);
}

/* Appends text[0..n) with "%%" read as "%". */
static size_t put_literal(char *out, size_t at, size_t size, const char *text, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (text[i] == '%' && i + 1 < n && text[i + 1] == '%')
            i++;
        if (at + 1 < size)
            out[at] = text[i];
        at++;
    }
    return at;
}

fc_code fc_pattern_path(const char *pattern, uint32_t number, char *out, size_t size, fc_error *err)
{
    conversion c;
    if (!find_conversion(pattern, &c))
        return fc_error_set(err, FC_ERR_USAGE, "\"%s\" needs one %%d (e.g. %%04d) for the frame number", pattern);
    char digits[32];
    snprintf(digits, sizeof digits, c.zero_pad ? "%0*u" : "%*u", c.width, (unsigned)number);
    size_t at = put_literal(out, 0, size, pattern, c.at);
    at = put_literal(out, at, size, digits, strlen(digits));
    at = put_literal(out, at, size, pattern + c.at + c.length, strlen(pattern + c.at + c.length));
    if (at >= size)
        return fc_error_set(err, FC_ERR_USAGE, "the file name of frame %u of \"%s\" is too long", (unsigned)number,
                            pattern);
    out[at] = '\0';
    return FC_OK;
}

/* ---- the growing list ---- */

static fc_code add_path(fc_render_inputs *in, const char *path, uint32_t number, fc_error *err)
{
    if (in->count >= MAX_FRAMES)
        return fc_error_set(err, FC_ERR_USAGE, "at most %u frames per render", MAX_FRAMES);
    if ((in->count & (in->count - 1)) == 0) {   /* grow at powers of two */
        uint32_t cap = in->count ? 2 * in->count : 1;
        char **paths = realloc(in->paths, cap * sizeof *paths);
        if (paths)
            in->paths = paths;
        uint32_t *numbers = realloc(in->numbers, cap * sizeof *numbers);
        if (numbers)
            in->numbers = numbers;
        if (!paths || !numbers)
            return fc_error_set(err, FC_ERR_NOMEM, "no memory for the list of frames");
    }
    in->paths[in->count] = strdup(path);
    if (!in->paths[in->count])
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the list of frames");
    in->numbers[in->count++] = number;
    return FC_OK;
}

/* ---- a frame pattern ---- */

/* The number a file name glob found for the pattern holds, when it matches exactly. */
static bool number_in(const char *name, const char *prefix, size_t prefix_len, const char *suffix, uint32_t *out)
{
    size_t len = strlen(name), suffix_len = strlen(suffix);
    if (len <= prefix_len + suffix_len || strncmp(name, prefix, prefix_len) != 0 ||
        strcmp(name + len - suffix_len, suffix) != 0)
        return false;
    uint64_t n = 0;
    for (size_t i = prefix_len; i < len - suffix_len; i++) {
        if (name[i] < '0' || name[i] > '9' || n > UINT32_MAX / 10)
            return false;
        n = n * 10 + (uint64_t)(name[i] - '0');
    }
    if (n > UINT32_MAX)
        return false;
    *out = (uint32_t)n;
    return true;
}

/* The lowest frame number of the pattern that exists. */
static fc_code first_existing(const char *pattern, uint32_t *first, fc_error *err)
{
    conversion c;
    if (!find_conversion(pattern, &c))
        return fc_error_set(err, FC_ERR_USAGE, "\"%s\" is not a frame pattern with one %%d", pattern);
    char prefix[PATH_CAP], suffix[PATH_CAP], wildcard[2 * PATH_CAP + 2];
    size_t prefix_len = put_literal(prefix, 0, sizeof prefix, pattern, c.at);
    const char *rest = pattern + c.at + c.length;
    size_t suffix_len = put_literal(suffix, 0, sizeof suffix, rest, strlen(rest));
    if (prefix_len >= sizeof prefix || suffix_len >= sizeof suffix)
        return fc_error_set(err, FC_ERR_USAGE, "the pattern \"%s\" is too long", pattern);
    prefix[prefix_len] = suffix[suffix_len] = '\0';
    snprintf(wildcard, sizeof wildcard, "%s*%s", prefix, suffix);
    glob_t g;
    bool found = false;
    if (glob(wildcard, 0, NULL, &g) == 0) {
        for (size_t i = 0; i < g.gl_pathc; i++) {
            uint32_t n;
            if (number_in(g.gl_pathv[i], prefix, prefix_len, suffix, &n) && (!found || n < *first)) {
                *first = n;
                found = true;
            }
        }
        globfree(&g);
    }
    if (!found)
        return fc_error_set(err, FC_ERR_USAGE, "no file matches the pattern \"%s\"", pattern);
    return FC_OK;
}

static fc_code expand_pattern(const char *pattern, const fc_frame_range *range, fc_render_inputs *out,
                              fc_error *err)
{
    uint32_t number = range->start;
    fc_code code = range->has_start ? FC_OK : first_existing(pattern, &number, err);
    char path[PATH_CAP];
    while (code == FC_OK) {
        if (range->has_end && number > range->end)
            break;
        code = fc_pattern_path(pattern, number, path, sizeof path, err);
        if (code != FC_OK)
            return code;
        /* Without --end the sequence is the run of frames that exist. */
        if (!range->has_end && access(path, F_OK) != 0) {
            if (out->count == 0)
                return fc_error_set(err, FC_ERR_USAGE, "%s: frame %u of \"%s\" does not exist", path,
                                    (unsigned)number, pattern);
            break;
        }
        code = add_path(out, path, number, err);
        if (number > UINT32_MAX - range->step)
            break;
        number += range->step;
    }
    return code;
}

/* ---- a {} pattern: every file with digits where {} is, by number ---- */

static bool in_range(const fc_frame_range *range, uint32_t first, uint32_t number)
{
    return (!range->has_start || number >= range->start) && (!range->has_end || number <= range->end) &&
           (number - first) % range->step == 0;
}

static fc_code expand_braces(const char *pattern, const fc_frame_range *range, fc_render_inputs *out,
                             fc_error *err)
{
    fc_brace_match *m;
    size_t count;
    fc_code code = fc_brace_matches(pattern, &m, &count, err);
    if (code != FC_OK)
        return code;
    /* --step counts from --start, else from the lowest number there is. */
    uint32_t first = range->has_start ? range->start : m[0].number;
    for (size_t i = 0; i < count && code == FC_OK; i++)
        if (m[i].number >= first && in_range(range, first, m[i].number))
            code = add_path(out, m[i].path, m[i].number, err);
    fc_brace_matches_free(m, count);
    if (code == FC_OK && out->count == 0)
        code = fc_error_set(err, FC_ERR_USAGE, "no file of \"%s\" is in the frame range given", pattern);
    return code;
}

/* ---- lists and globs ---- */

static int version_order(const void *a, const void *b)
{
    return strverscmp(*(char *const *)a, *(char *const *)b);
}

static fc_code expand_glob(const char *arg, fc_render_inputs *out, fc_error *err)
{
    glob_t g;
    int rc = glob(arg, 0, NULL, &g);
    if (rc != 0) {
        if (rc != GLOB_NOMATCH)
            globfree(&g);
        return rc == GLOB_NOMATCH ? fc_error_set(err, FC_ERR_USAGE, "\"%s\" matches no file", arg)
                                  : fc_error_set(err, FC_ERR_IO, "cannot expand \"%s\"", arg);
    }
    qsort(g.gl_pathv, g.gl_pathc, sizeof *g.gl_pathv, version_order);
    fc_code code = FC_OK;
    for (size_t i = 0; i < g.gl_pathc && code == FC_OK; i++)
        code = add_path(out, g.gl_pathv[i], out->count, err);
    globfree(&g);
    return code;
}

fc_code fc_render_inputs_expand(const char *const *args, uint32_t arg_count, const fc_frame_range *range,
                                fc_render_inputs *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    bool printf_pattern = arg_count == 1 && fc_is_frame_pattern(args[0]);
    bool brace_pattern = arg_count == 1 && !printf_pattern && fc_is_brace_pattern(args[0]);
    bool pattern = printf_pattern || brace_pattern;
    for (uint32_t i = 0; i < arg_count && !pattern; i++)
        if (fc_is_frame_pattern(args[i]) || fc_is_brace_pattern(args[i]))
            return fc_error_set(err, FC_ERR_USAGE, "a frame pattern (\"%s\") must be the only input", args[i]);
    if (!pattern && (range->has_start || range->has_end || range->step != 1))
        return fc_error_set(err, FC_ERR_USAGE, "--start, --end and --step need a frame pattern such as frame_%%04d.ply or frame_{}.ply");
    if (range->has_start && range->has_end && range->end < range->start)
        return fc_error_set(err, FC_ERR_USAGE, "--end %u is before --start %u", (unsigned)range->end,
                            (unsigned)range->start);
    fc_code code = FC_OK;
    if (printf_pattern)
        code = expand_pattern(args[0], range, out, err);
    else if (brace_pattern)
        code = expand_braces(args[0], range, out, err);
    for (uint32_t i = 0; i < arg_count && !pattern && code == FC_OK; i++)
        code = strpbrk(args[i], "*?[") ? expand_glob(args[i], out, err) : add_path(out, args[i], out->count, err);
    if (code == FC_OK && out->count == 0)
        code = fc_error_set(err, FC_ERR_USAGE, "render needs at least one particle file");
    return code;
}

void fc_render_inputs_free(fc_render_inputs *in)
{
    for (uint32_t i = 0; i < in->count; i++)
        free(in->paths[i]);
    free(in->paths);
    free(in->numbers);
    memset(in, 0, sizeof *in);
}
