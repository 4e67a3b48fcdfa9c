/* reader_npy.c — numpy's .npy arrays of particle positions: shape (N, 3),
 * float32 or float64, either byte order, C or Fortran order.
 *
 * Layout (numpy/lib/format.py): "\x93NUMPY", major and minor version bytes, the
 * header's length (uint16 little-endian in version 1, uint32 in 2 and 3), then
 * the header: a Python dict literal such as
 *     {'descr': '<f4', 'fortran_order': False, 'shape': (1000, 3), }
 * padded with spaces to a newline; the array's bytes follow it. The dict is
 * parsed here with the little grammar numpy's writer uses (strings, True/False,
 * tuples of integers), never evaluated. */
#include "reader_formats.h"

#include <stdio.h>
#include <string.h>
#include "fc_error.h"
#include "reader_fields.h"

enum { NPY_MAGIC_BYTES = 6, NPY_MAX_DIMENSIONS = 8 };

typedef struct npy_header {
    fc_span descr;
    bool have_descr, have_order, have_shape;
    bool fortran_order;
    size_t dimensions;
    uint64_t shape[NPY_MAX_DIMENSIONS];
    fc_scalar_type type;
    bool big_endian;
} npy_header;

/* ---- the header dict ---- */

static void skip_space(fc_span *s)
{
    while (s->len > 0 && (s->ptr[0] == ' ' || s->ptr[0] == '\t' || s->ptr[0] == '\n' || s->ptr[0] == '\r')) {
        s->ptr++;
        s->len--;
    }
}

/* Consumes ch (after spaces); false when the next character is another one. */
static bool take(fc_span *s, char ch)
{
    skip_space(s);
    if (s->len == 0 || s->ptr[0] != ch)
        return false;
    s->ptr++;
    s->len--;
    return true;
}

/* A '...' or "..." literal without escapes, as numpy writes keys and dtype strings. */
static bool take_string(fc_span *s, fc_span *out)
{
    skip_space(s);
    if (s->len == 0 || (s->ptr[0] != '\'' && s->ptr[0] != '"'))
        return false;
    char quote = s->ptr[0];
    const char *end = memchr(s->ptr + 1, quote, s->len - 1);
    if (end == NULL)
        return false;
    out->ptr = s->ptr + 1;
    out->len = (size_t)(end - out->ptr);
    s->len -= (size_t)(end + 1 - s->ptr);
    s->ptr = end + 1;
    return true;
}

static bool take_word(fc_span *s, const char *word)
{
    skip_space(s);
    size_t n = strlen(word);
    if (s->len < n || memcmp(s->ptr, word, n) != 0)
        return false;
    s->ptr += n;
    s->len -= n;
    return true;
}

static bool take_count(fc_span *s, uint64_t *out)
{
    skip_space(s);
    size_t n = 0;
    while (n < s->len && s->ptr[n] >= '0' && s->ptr[n] <= '9')
        n++;
    /* Python 2 era files may write 1000L. */
    if (!fc_span_to_count((fc_span){ s->ptr, n }, out))
        return false;
    s->ptr += n;
    s->len -= n;
    if (s->len > 0 && s->ptr[0] == 'L')
        s->ptr++, s->len--;
    return true;
}

/* (N, 3) or (N,) or (): integers, a trailing comma allowed. */
static fc_code parse_shape(const fc_cursor *c, fc_span *s, npy_header *h, fc_error *err)
{
    if (!take(s, '('))
        return fc_cursor_fail(c, err, "header: 'shape' is not a tuple");
    while (!take(s, ')')) {
        if (h->dimensions == NPY_MAX_DIMENSIONS)
            return fc_cursor_fail(c, err, "header: 'shape' has more than %d dimensions", NPY_MAX_DIMENSIONS);
        if (!take_count(s, &h->shape[h->dimensions]))
            return fc_cursor_fail(c, err, "header: 'shape' holds something other than non-negative integers");
        h->dimensions++;
        if (!take(s, ',') && !(skip_space(s), s->len > 0 && s->ptr[0] == ')'))
            return fc_cursor_fail(c, err, "header: 'shape' is not a tuple of integers");
    }
    h->have_shape = true;
    return FC_OK;
}

static fc_code parse_entry(const fc_cursor *c, fc_span *s, npy_header *h, fc_error *err)
{
    char quoted[FC_QUOTE_MAX];
    fc_span key;
    if (!take_string(s, &key) || !take(s, ':'))
        return fc_cursor_fail(c, err, "header: expected 'key': value in the dict");
    if (fc_span_iequals(key, "descr")) {
        if (!take_string(s, &h->descr))
            return fc_cursor_fail(c, err, "header: 'descr' is not a simple dtype string (structured arrays are "
                                          "not supported: save an (N, 3) float array)");
        h->have_descr = true;
        return FC_OK;
    }
    if (fc_span_iequals(key, "fortran_order")) {
        if (take_word(s, "True"))
            h->fortran_order = true;
        else if (!take_word(s, "False"))
            return fc_cursor_fail(c, err, "header: 'fortran_order' is neither True nor False");
        h->have_order = true;
        return FC_OK;
    }
    if (fc_span_iequals(key, "shape"))
        return parse_shape(c, s, h, err);
    return fc_cursor_fail(c, err, "header: unexpected key '%s'", fc_span_quote(key, quoted, sizeof quoted));
}

static fc_code parse_dict(const fc_cursor *c, fc_span s, npy_header *h, fc_error *err)
{
    if (!take(&s, '{'))
        return fc_cursor_fail(c, err, "header is not a dict");
    while (!take(&s, '}')) {
        fc_code code = parse_entry(c, &s, h, err);
        if (code != FC_OK)
            return code;
        if (!take(&s, ',') && !(skip_space(&s), s.len > 0 && s.ptr[0] == '}'))
            return fc_cursor_fail(c, err, "header: expected ',' or '}' after a value");
    }
    if (!h->have_descr || !h->have_order || !h->have_shape)
        return fc_cursor_fail(c, err, "header lacks %s", !h->have_descr ? "'descr'" : !h->have_order ? "'fortran_order'"
                                                                                                    : "'shape'");
    return FC_OK;
}

/* ---- checks ---- */

/* '<f4' '<f8' (or '>' '=' '|' byte orders: '=' and '|' are the writer's native order, little-endian on every
 * machine numpy files come from in practice). */
static fc_code check_descr(const fc_cursor *c, npy_header *h, fc_error *err)
{
    char quoted[FC_QUOTE_MAX];
    fc_span d = h->descr;
    if (d.len == 3 && (d.ptr[0] == '<' || d.ptr[0] == '>' || d.ptr[0] == '=' || d.ptr[0] == '|') && d.ptr[1] == 'f' &&
        (d.ptr[2] == '4' || d.ptr[2] == '8')) {
        h->big_endian = d.ptr[0] == '>';
        h->type = d.ptr[2] == '4' ? FC_SCALAR_F32 : FC_SCALAR_F64;
        return FC_OK;
    }
    return fc_cursor_fail(c, err, "dtype '%s' is not supported (float32 '<f4' or float64 '<f8')",
                          fc_span_quote(d, quoted, sizeof quoted));
}

static fc_code check_shape(const fc_cursor *c, const npy_header *h, fc_error *err)
{
    if (h->dimensions == 2 && h->shape[1] == 3)
        return FC_OK;
    char shape[96] = "(";
    for (size_t i = 0; i < h->dimensions; i++) {
        size_t used = strlen(shape);
        snprintf(shape + used, sizeof shape - used, "%llu%s", (unsigned long long)h->shape[i],
                 i + 1 < h->dimensions || h->dimensions == 1 ? ", " : "");
    }
    strncat(shape, ")", sizeof shape - strlen(shape) - 1);
    return fc_cursor_fail(c, err, "shape %s is not (N, 3): expected one x y z row per particle", shape);
}

/* ---- file ---- */

static fc_code read_header(fc_cursor *c, npy_header *h, fc_error *err)
{
    if (c->size < NPY_MAGIC_BYTES || memcmp(c->data, "\x93NUMPY", NPY_MAGIC_BYTES) != 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: not a numpy .npy file (no \\x93NUMPY magic)", c->name);
    c->pos = NPY_MAGIC_BYTES;
    double major = 0, minor = 0, length = 0;
    if (!fc_cursor_read_scalar(c, FC_SCALAR_U8, false, &major) || !fc_cursor_read_scalar(c, FC_SCALAR_U8, false, &minor))
        return fc_cursor_fail(c, err, "file ends in the version");
    if (major < 1 || major > 3 || minor != 0)
        return fc_cursor_fail(c, err, ".npy version %g.%g is not supported (1.0, 2.0 or 3.0)", major, minor);
    if (!fc_cursor_read_scalar(c, major == 1 ? FC_SCALAR_U16 : FC_SCALAR_U32, false, &length))
        return fc_cursor_fail(c, err, "file ends in the header length");
    if (length > (double)fc_cursor_remaining(c))
        return fc_cursor_fail(c, err, "header of %.0f bytes runs past the end of the data", length);
    fc_span dict = { (const char *)c->data + c->pos, (size_t)length };
    fc_code code = parse_dict(c, dict, h, err);
    c->pos += (size_t)length;
    if (code == FC_OK)
        code = check_descr(c, h, err);
    if (code == FC_OK)
        code = check_shape(c, h, err);
    return code;
}

static fc_code read_values(fc_cursor *c, const npy_header *h, fc_frame *frame, fc_error *err)
{
    uint64_t n = h->shape[0];
    size_t size = fc_scalar_size(h->type);
    if (n > fc_cursor_remaining(c) / size / 3)
        return fc_cursor_fail(c, err, "%llu x 3 values of %zu bytes cannot fit in the %zu bytes left",
                              (unsigned long long)n, size, fc_cursor_remaining(c));
    fc_code code = fc_reader_alloc_frame(c, frame, n, 0, err);
    if (code != FC_OK)
        return code;
    /* Row i, column k lies at (3i + k) in C order and at (k n + i) in Fortran order. */
    for (uint64_t at = 0; at < 3 * n; at++) {
        uint64_t i = h->fortran_order ? at % n : at / 3;
        fc_field axis = (fc_field)(FC_FIELD_X + (h->fortran_order ? at / n : at % 3));
        double value = 0.0;
        fc_cursor_read_scalar(c, h->type, h->big_endian, &value); /* fits: checked above */
        if (!(h->type == FC_SCALAR_F64 ? fc_field_store_position64(c, frame, i, axis, value)
                                       : fc_field_store(frame, i, axis, value))) {
            c->pos -= size;
            return fc_field_reject(c, err, i, axis, value);
        }
    }
    if (fc_cursor_remaining(c) != 0)
        return fc_cursor_fail(c, err, "%zu bytes after the array's %llu x 3 values", fc_cursor_remaining(c),
                              (unsigned long long)n);
    return FC_OK;
}

fc_code fc_read_npy(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    c->binary = true;
    npy_header h;
    memset(&h, 0, sizeof h);
    fc_code code = read_header(c, &h, err);
    if (code == FC_OK)
        code = read_values(c, &h, frame, err);
    return code;
}
