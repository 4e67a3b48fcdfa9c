/* reader_vtkxml_data.c — base64 and raw sources, VTK's block headers and zlib blocks. */
#include "reader_vtkxml_data.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "reader_inflate.h"

/* Deflate's largest ratio (1032:1) bounds what a block may claim to inflate to. */
enum { DEFLATE_MAX_RATIO = 1032 };

void fc_vx_source_init(fc_vx_source *s, const uint8_t *data, size_t size, bool base64)
{
    memset(s, 0, sizeof *s);
    s->data = data;
    s->size = size;
    s->base64 = base64;
}

static int base64_value(uint8_t ch)
{
    if (ch >= 'A' && ch <= 'Z')
        return ch - 'A';
    if (ch >= 'a' && ch <= 'z')
        return ch - 'a' + 26;
    if (ch >= '0' && ch <= '9')
        return ch - '0' + 52;
    if (ch == '+')
        return 62;
    if (ch == '/')
        return 63;
    return -1;
}

static bool is_space(uint8_t ch)
{
    return ch == ' ' || ch == '\n' || ch == '\r' || ch == '\t';
}

/* The next four non-space characters as one quad: 1..3 bytes, fewer at '=' padding.
 * 0 at the end of the text (or where base64 stops: the "</AppendedData>" after the data); -1 on bad text. */
static int decode_quad(fc_vx_source *s, uint8_t out[3])
{
    int values[4], count = 0;
    while (count < 4) {
        while (s->pos < s->size && is_space(s->data[s->pos]))
            s->pos++;
        if (s->pos >= s->size || s->data[s->pos] == '<')
            return count == 0 ? 0 : -1;
        uint8_t ch = s->data[s->pos++];
        if (ch == '=') {
            if (count < 2)
                return -1;
            values[count++] = -2; /* padding */
            continue;
        }
        int v = base64_value(ch);
        if (v < 0 || (count > 0 && values[count - 1] == -2))
            return -1;
        values[count++] = v;
    }
    int bytes = values[2] == -2 ? 1 : values[3] == -2 ? 2 : 3;
    uint32_t bits = ((uint32_t)values[0] << 18) | ((uint32_t)values[1] << 12) |
                    ((uint32_t)(values[2] < 0 ? 0 : values[2]) << 6) | (uint32_t)(values[3] < 0 ? 0 : values[3]);
    out[0] = (uint8_t)(bits >> 16);
    out[1] = (uint8_t)(bits >> 8);
    out[2] = (uint8_t)bits;
    return bytes;
}

/* Copies n bytes out of s; false when the data ends first or the base64 text is bad. */
static bool source_read(fc_vx_source *s, uint8_t *out, size_t n, bool *bad_text)
{
    if (!s->base64) {
        if (n > s->size - s->pos)
            return false;
        memcpy(out, s->data + s->pos, n);
        s->pos += n;
        return true;
    }
    while (n > 0) {
        if (s->pending_count == 0) {
            uint8_t quad[3];
            int got = decode_quad(s, quad);
            if (got <= 0) {
                *bad_text = got < 0;
                return false;
            }
            /* Keep them in order: hand out from the front. */
            memcpy(s->pending, quad, (size_t)got);
            s->pending_count = (size_t)got;
        }
        size_t take = s->pending_count < n ? s->pending_count : n;
        memcpy(out, s->pending, take);
        memmove(s->pending, s->pending + take, s->pending_count - take);
        s->pending_count -= take;
        out += take;
        n -= take;
    }
    return true;
}

/* An upper bound on the bytes s can still give: what bounds allocations before reading. */
static size_t source_bound(const fc_vx_source *s)
{
    size_t left = s->size - s->pos;
    return s->base64 ? left / 4 * 3 + 3 + s->pending_count : left;
}

static fc_code run_out(const char *name, const char *what, bool bad_text, const char *part, fc_error *err)
{
    if (bad_text)
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s: invalid base64 text in the %s", name, what, part);
    return fc_error_set(err, FC_ERR_PARSE, "%s: %s: data ends in the %s", name, what, part);
}

static bool read_word(fc_vx_source *s, const fc_vx_encoding *e, uint64_t *word, bool *bad_text)
{
    uint8_t bytes[8];
    size_t size = e->header64 ? 8 : 4;
    if (!source_read(s, bytes, size, bad_text))
        return false;
    *word = 0;
    for (size_t i = 0; i < size; i++)
        *word = (*word << 8) | bytes[e->big_endian ? i : size - 1 - i];
    return true;
}

static fc_code read_plain(fc_vx_source *s, const fc_vx_encoding *e, size_t expected, const char *name,
                          const char *what, uint8_t *out, fc_error *err)
{
    uint64_t stated = 0;
    bool bad_text = false;
    if (!read_word(s, e, &stated, &bad_text))
        return run_out(name, what, bad_text, "header", err);
    if (stated != expected)
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s: header says %llu bytes, the array holds %zu", name, what,
                            (unsigned long long)stated, expected);
    if (!source_read(s, out, expected, &bad_text))
        return run_out(name, what, bad_text, "data", err);
    return FC_OK;
}

/* The compressed header: block count, block size, last block's size (0: a full block), each block's compressed size. */
typedef struct zlib_header {
    uint64_t blocks, block_size, last_size;
    uint64_t *compressed; /* blocks entries */
} zlib_header;

static fc_code read_zlib_header(fc_vx_source *s, const fc_vx_encoding *e, size_t expected, const char *name,
                                const char *what, zlib_header *h, fc_error *err)
{
    bool bad_text = false;
    if (!read_word(s, e, &h->blocks, &bad_text) || !read_word(s, e, &h->block_size, &bad_text) ||
        !read_word(s, e, &h->last_size, &bad_text))
        return run_out(name, what, bad_text, "compression header", err);
    size_t word = e->header64 ? 8 : 4;
    if (h->blocks > source_bound(s) / word)
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s: %llu compressed blocks cannot fit in the data left", name, what,
                            (unsigned long long)h->blocks);
    if (h->blocks == 0 || h->block_size == 0 || h->last_size > h->block_size)
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s: bad compression header (%llu blocks of %llu bytes, last %llu)",
                            name, what, (unsigned long long)h->blocks, (unsigned long long)h->block_size,
                            (unsigned long long)h->last_size);
    uint64_t last = h->last_size ? h->last_size : h->block_size;
    /* (blocks - 1) x block_size + last == expected, without overflow; VTK states its block size (32 KiB) even
     * for one short block. */
    uint64_t rest = last <= expected ? expected - last : 0;
    bool sums = last <= expected && (h->blocks == 1 ? rest == 0
                                                    : rest % h->block_size == 0 && rest / h->block_size == h->blocks - 1);
    if (!sums)
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s: %llu blocks of %llu bytes (last %llu) do not make the array's %zu bytes",
                            name, what, (unsigned long long)h->blocks, (unsigned long long)h->block_size,
                            (unsigned long long)h->last_size, expected);
    h->compressed = malloc((size_t)h->blocks * sizeof *h->compressed);
    if (h->compressed == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: %s: cannot allocate the block table", name, what);
    for (uint64_t i = 0; i < h->blocks; i++) {
        if (!read_word(s, e, &h->compressed[i], &bad_text))
            return run_out(name, what, bad_text, "compression header", err);
        uint64_t inflated = i + 1 == h->blocks ? last : h->block_size;
        if (h->compressed[i] > source_bound(s) || inflated / DEFLATE_MAX_RATIO > h->compressed[i])
            return fc_error_set(err, FC_ERR_PARSE, "%s: %s: block %llu: %llu compressed bytes for %llu cannot be right",
                                name, what, (unsigned long long)i, (unsigned long long)h->compressed[i],
                                (unsigned long long)inflated);
    }
    return FC_OK;
}

static fc_code read_zlib_blocks(fc_vx_source *s, const zlib_header *h, const char *name, const char *what,
                                uint8_t *out, fc_error *err)
{
    size_t at = 0;
    for (uint64_t i = 0; i < h->blocks; i++) {
        size_t inflated = (size_t)(i + 1 == h->blocks && h->last_size ? h->last_size : h->block_size);
        size_t packed_size = (size_t)h->compressed[i];
        uint8_t *packed = malloc(packed_size > 0 ? packed_size : 1);
        if (packed == NULL)
            return fc_error_set(err, FC_ERR_NOMEM, "%s: %s: cannot allocate %zu bytes", name, what, packed_size);
        bool bad_text = false;
        if (!source_read(s, packed, packed_size, &bad_text)) {
            free(packed);
            return run_out(name, what, bad_text, "compressed data", err);
        }
        uint8_t *plain = NULL;
        size_t plain_size = 0;
        char block_what[160];
        snprintf(block_what, sizeof block_what, "%s: block %llu", what, (unsigned long long)i);
        fc_code code = fc_inflate(name, block_what, packed, packed_size, false, inflated, &plain, &plain_size, err);
        free(packed);
        if (code != FC_OK)
            return code;
        memcpy(out + at, plain, plain_size);
        free(plain);
        at += plain_size;
    }
    return FC_OK;
}

fc_code fc_vx_read_block(fc_vx_source *s, const fc_vx_encoding *encoding, size_t expected, const char *name,
                         const char *what, uint8_t **out, fc_error *err)
{
    *out = NULL;
    zlib_header h = { 0, 0, 0, NULL };
    fc_code code = FC_OK;
    if (encoding->compressed)
        code = read_zlib_header(s, encoding, expected, name, what, &h, err);
    else if (expected > source_bound(s))
        code = fc_error_set(err, FC_ERR_PARSE, "%s: %s: %zu bytes cannot fit in the data left", name, what, expected);
    if (code == FC_OK) {
        *out = malloc(expected > 0 ? expected : 1);
        if (*out == NULL)
            code = fc_error_set(err, FC_ERR_NOMEM, "%s: %s: cannot allocate %zu bytes", name, what, expected);
    }
    if (code == FC_OK)
        code = encoding->compressed ? read_zlib_blocks(s, &h, name, what, *out, err)
                                    : read_plain(s, encoding, expected, name, what, *out, err);
    free(h.compressed);
    if (code != FC_OK) {
        free(*out);
        *out = NULL;
    }
    return code;
}

bool fc_vx_scalar_type(const char *name, fc_scalar_type *type)
{
    static const struct {
        const char *name;
        fc_scalar_type type;
    } types[] = {{"Int8", FC_SCALAR_I8},   {"UInt8", FC_SCALAR_U8},   {"Int16", FC_SCALAR_I16},
                 {"UInt16", FC_SCALAR_U16}, {"Int32", FC_SCALAR_I32}, {"UInt32", FC_SCALAR_U32},
                 {"Int64", FC_SCALAR_I64}, {"UInt64", FC_SCALAR_U64}, {"Float32", FC_SCALAR_F32},
                 {"Float64", FC_SCALAR_F64}};
    for (size_t i = 0; name != NULL && i < sizeof types / sizeof types[0]; i++)
        if (strcmp(name, types[i].name) == 0)
            return *type = types[i].type, true;
    return false;
}
