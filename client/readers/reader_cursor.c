/* reader_cursor.c — bounded cursor, spans and scalar decoding for the particle readers. */
#include "reader_cursor.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"

void fc_cursor_init(fc_cursor *c, const uint8_t *data, size_t size, const char *name)
{
    c->data = data;
    c->size = size;
    c->pos = 0;
    c->line_at_pos = 1;
    c->line = 1;
    c->binary = false;
    c->name = name;
    c->options = NULL;
    c->extras = NULL;
    c->positions64 = NULL;
    c->adoptable = NULL;
}

size_t fc_cursor_remaining(const fc_cursor *c)
{
    return c->size - c->pos;
}

fc_code fc_cursor_fail(const fc_cursor *c, fc_error *err, const char *fmt, ...)
{
    char reason[FC_ERROR_MESSAGE_MAX];
    va_list args;
    va_start(args, fmt);
    vsnprintf(reason, sizeof reason, fmt, args);
    va_end(args);
    if (c->binary)
        return fc_error_set(err, FC_ERR_PARSE, "%s: byte offset %zu: %s", c->name, c->pos, reason);
    return fc_error_set(err, FC_ERR_PARSE, "%s: line %zu: %s", c->name, c->line, reason);
}

/* ---- text ---- */

static bool is_space(char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n' || ch == '\v' || ch == '\f';
}

static char ascii_lower(char ch)
{
    return (ch >= 'A' && ch <= 'Z') ? (char)(ch - 'A' + 'a') : ch;
}

bool fc_cursor_next_line(fc_cursor *c, fc_span *line)
{
    if (c->pos >= c->size)
        return false;
    const char *start = (const char *)c->data + c->pos;
    const char *newline = memchr(start, '\n', c->size - c->pos);
    size_t len = newline ? (size_t)(newline - start) : c->size - c->pos;
    c->line = c->line_at_pos;
    c->pos += len;
    if (newline) {
        c->pos++;
        c->line_at_pos++;
    }
    if (len > 0 && start[len - 1] == '\r')
        len--;
    line->ptr = start;
    line->len = len;
    return true;
}

bool fc_cursor_next_nonblank_line(fc_cursor *c, fc_span *line)
{
    while (fc_cursor_next_line(c, line)) {
        if (!fc_span_is_blank(*line))
            return true;
    }
    return false;
}

bool fc_cursor_next_token(fc_cursor *c, fc_span *token)
{
    const char *text = (const char *)c->data;
    while (c->pos < c->size && is_space(text[c->pos])) {
        if (text[c->pos] == '\n')
            c->line_at_pos++;
        c->pos++;
    }
    if (c->pos >= c->size)
        return false;
    size_t start = c->pos;
    while (c->pos < c->size && !is_space(text[c->pos]))
        c->pos++;
    c->line = c->line_at_pos;
    token->ptr = text + start;
    token->len = c->pos - start;
    return true;
}

bool fc_cursor_peek_keyword(const fc_cursor *c, const char *keyword)
{
    fc_cursor ahead = *c;
    fc_span token;
    if (c->binary) {
        /* Binary data may start with bytes that look like whitespace: the keyword must start at pos. */
        token.ptr = (const char *)c->data + c->pos;
        token.len = 0;
        while (token.len < c->size - c->pos && !is_space(token.ptr[token.len]))
            token.len++;
        return fc_span_iequals(token, keyword);
    }
    return fc_cursor_next_token(&ahead, &token) && fc_span_iequals(token, keyword);
}

fc_span fc_span_trim(fc_span s)
{
    while (s.len > 0 && is_space(s.ptr[0])) {
        s.ptr++;
        s.len--;
    }
    while (s.len > 0 && is_space(s.ptr[s.len - 1]))
        s.len--;
    return s;
}

bool fc_span_is_blank(fc_span s)
{
    return fc_span_trim(s).len == 0;
}

bool fc_span_istarts_with(fc_span s, const char *prefix)
{
    size_t n = strlen(prefix);
    if (s.len < n)
        return false;
    for (size_t i = 0; i < n; i++) {
        if (ascii_lower(s.ptr[i]) != ascii_lower(prefix[i]))
            return false;
    }
    return true;
}

bool fc_span_iequals(fc_span s, const char *word)
{
    return s.len == strlen(word) && fc_span_istarts_with(s, word);
}

bool fc_span_next_token(fc_span *rest, fc_span *token)
{
    while (rest->len > 0 && is_space(rest->ptr[0])) {
        rest->ptr++;
        rest->len--;
    }
    if (rest->len == 0)
        return false;
    size_t len = 0;
    while (len < rest->len && !is_space(rest->ptr[len]))
        len++;
    token->ptr = rest->ptr;
    token->len = len;
    rest->ptr += len;
    rest->len -= len;
    return true;
}

size_t fc_span_count_tokens(fc_span s)
{
    size_t count = 0;
    fc_span token;
    while (fc_span_next_token(&s, &token))
        count++;
    return count;
}

bool fc_span_next_field(fc_span *rest, char separator, fc_span *field)
{
    if (rest->ptr == NULL)
        return false;
    const char *sep = memchr(rest->ptr, separator, rest->len);
    field->ptr = rest->ptr;
    if (sep == NULL) {
        field->len = rest->len;
        rest->ptr = NULL; /* used up: the last field has been handed out */
        rest->len = 0;
        return true;
    }
    field->len = (size_t)(sep - rest->ptr);
    rest->ptr = sep + 1;
    rest->len -= field->len + 1;
    return true;
}

bool fc_span_to_double(fc_span s, double *out)
{
    /* strtod needs a terminated string; no sensible number is this long. */
    char buf[64];
    if (s.len == 0 || s.len >= sizeof buf || is_space(s.ptr[0]))
        return false;
    memcpy(buf, s.ptr, s.len);
    buf[s.len] = '\0';
    char *end = NULL;
    double value = strtod(buf, &end);
    if (end != buf + s.len)
        return false;
    *out = value;
    return true;
}

bool fc_span_to_count(fc_span s, uint64_t *out)
{
    if (s.len == 0)
        return false;
    uint64_t value = 0;
    for (size_t i = 0; i < s.len; i++) {
        char ch = s.ptr[i];
        if (ch < '0' || ch > '9')
            return false;
        uint64_t digit = (uint64_t)(ch - '0');
        if (value > (UINT64_MAX - digit) / 10)
            return false;
        value = value * 10 + digit;
    }
    *out = value;
    return true;
}

const char *fc_span_quote(fc_span s, char *buf, size_t bufsize)
{
    const char *ellipsis = "...";
    size_t room = bufsize - 1;
    bool cut = s.len > room;
    size_t n = cut ? room - strlen(ellipsis) : s.len;
    for (size_t i = 0; i < n; i++) {
        unsigned char ch = (unsigned char)s.ptr[i];
        buf[i] = (ch >= 0x20 && ch < 0x7f) ? (char)ch : '?';
    }
    buf[n] = '\0';
    if (cut)
        strcat(buf, ellipsis);
    return buf;
}

/* ---- binary ---- */

size_t fc_scalar_size(fc_scalar_type type)
{
    switch (type) {
    case FC_SCALAR_I8:
    case FC_SCALAR_U8:
        return 1;
    case FC_SCALAR_I16:
    case FC_SCALAR_U16:
        return 2;
    case FC_SCALAR_I32:
    case FC_SCALAR_U32:
    case FC_SCALAR_F32:
        return 4;
    case FC_SCALAR_I64:
    case FC_SCALAR_U64:
    case FC_SCALAR_F64:
        return 8;
    }
    return 1;
}

/* Assembles size bytes in file order into an unsigned integer, independent of the host's byte order. */
static uint64_t load_bits(const uint8_t *p, size_t size, bool big_endian)
{
    uint64_t bits = 0;
    for (size_t i = 0; i < size; i++) {
        size_t byte = big_endian ? i : size - 1 - i;
        bits = (bits << 8) | p[byte];
    }
    return bits;
}

static double bits_to_double(uint64_t bits, fc_scalar_type type)
{
    switch (type) {
    case FC_SCALAR_I8:
        return (double)(int8_t)(uint8_t)bits;
    case FC_SCALAR_U8:
        return (double)(uint8_t)bits;
    case FC_SCALAR_I16:
        return (double)(int16_t)(uint16_t)bits;
    case FC_SCALAR_U16:
        return (double)(uint16_t)bits;
    case FC_SCALAR_I32:
        return (double)(int32_t)(uint32_t)bits;
    case FC_SCALAR_U32:
        return (double)(uint32_t)bits;
    case FC_SCALAR_I64:
        return (double)(int64_t)bits;
    case FC_SCALAR_U64:
        return (double)bits;
    case FC_SCALAR_F32: {
        uint32_t narrow = (uint32_t)bits;
        float f;
        memcpy(&f, &narrow, sizeof f);
        return (double)f;
    }
    case FC_SCALAR_F64: {
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    }
    return 0.0;
}

bool fc_cursor_read_scalar(fc_cursor *c, fc_scalar_type type, bool big_endian, double *out)
{
    size_t size = fc_scalar_size(type);
    if (fc_cursor_remaining(c) < size)
        return false;
    *out = bits_to_double(load_bits(c->data + c->pos, size, big_endian), type);
    c->pos += size;
    return true;
}

bool fc_cursor_skip_items(fc_cursor *c, uint64_t count, size_t item_size)
{
    if (item_size != 0 && count > fc_cursor_remaining(c) / item_size)
        return false;
    c->pos += (size_t)count * item_size;
    return true;
}
