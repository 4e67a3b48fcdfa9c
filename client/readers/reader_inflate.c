/* reader_inflate.c — bounded zlib/gzip inflation for the particle readers. */
#include "reader_inflate.h"

#include <limits.h>
#include <stdlib.h>
#include <zlib.h>
#include "fc_error.h"

/* Deflate never compresses better than about 1032:1; a larger output is not a real stream. */
enum { DEFLATE_MAX_RATIO = 1032, INFLATE_FIRST_GUESS = 1 << 16 };

bool fc_is_gzip(const uint8_t *data, size_t size)
{
    return size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
}

static size_t output_limit(size_t in_size, size_t expected_size)
{
    if (expected_size != 0)
        return expected_size;
    if (in_size > (SIZE_MAX - 64) / DEFLATE_MAX_RATIO)
        return SIZE_MAX;
    return in_size * DEFLATE_MAX_RATIO + 64;
}

/* Makes room for more output: doubles the buffer, never beyond limit. */
static bool grow(uint8_t **buffer, size_t *capacity, size_t limit)
{
    size_t wanted = *capacity == 0 ? INFLATE_FIRST_GUESS : *capacity;
    if (*capacity != 0)
        wanted = *capacity > limit / 2 ? limit : *capacity * 2;
    if (wanted > limit)
        wanted = limit;
    uint8_t *bigger = realloc(*buffer, wanted > 0 ? wanted : 1);
    if (bigger == NULL)
        return false;
    *buffer = bigger;
    *capacity = wanted;
    return true;
}

/* Feeds input in pieces zlib's 32-bit counters can hold. */
static void feed(z_stream *z, const uint8_t *in, size_t in_size, size_t *consumed)
{
    if (z->avail_in == 0 && *consumed < in_size) {
        size_t piece = in_size - *consumed;
        if (piece > UINT_MAX)
            piece = UINT_MAX;
        z->next_in = (Bytef *)(uintptr_t)(in + *consumed);
        z->avail_in = (uInt)piece;
        *consumed += piece;
    }
}

static fc_code inflate_all(z_stream *z, const char *name, const char *what, const uint8_t *in, size_t in_size,
                           size_t limit, uint8_t **out, size_t *out_size, fc_error *err)
{
    size_t consumed = 0, capacity = 0, produced = 0;
    for (;;) {
        if (produced == capacity) {
            if (capacity == limit)
                return fc_error_set(err, FC_ERR_PARSE, "%s: %s: inflates to more than %zu bytes", name, what, limit);
            if (!grow(out, &capacity, limit))
                return fc_error_set(err, FC_ERR_NOMEM, "%s: %s: cannot allocate %zu bytes to inflate into", name,
                                    what, capacity);
        }
        feed(z, in, in_size, &consumed);
        size_t room = capacity - produced;
        z->next_out = *out + produced;
        z->avail_out = room > UINT_MAX ? UINT_MAX : (uInt)room;
        uInt before = z->avail_out;
        int status = inflate(z, Z_NO_FLUSH);
        produced += before - z->avail_out;
        if (status == Z_STREAM_END) {
            *out_size = produced;
            if (z->avail_in != 0 || consumed != in_size)
                return fc_error_set(err, FC_ERR_PARSE, "%s: %s: %zu bytes after the end of the compressed stream",
                                    name, what, (size_t)z->avail_in + (in_size - consumed));
            return FC_OK;
        }
        if (status == Z_BUF_ERROR && z->avail_in == 0 && consumed == in_size)
            return fc_error_set(err, FC_ERR_PARSE, "%s: %s: compressed stream is truncated", name, what);
        if (status != Z_OK && status != Z_BUF_ERROR) {
            if (status == Z_MEM_ERROR)
                return fc_error_set(err, FC_ERR_NOMEM, "%s: %s: zlib is out of memory", name, what);
            return fc_error_set(err, FC_ERR_PARSE, "%s: %s: corrupt compressed data (%s)", name, what,
                                z->msg ? z->msg : "zlib error");
        }
    }
}

fc_code fc_inflate(const char *name, const char *what, const uint8_t *in, size_t in_size, bool gzip,
                   size_t expected_size, uint8_t **out, size_t *out_size, fc_error *err)
{
    *out = NULL;
    *out_size = 0;
    z_stream z = { 0 };
    /* 16 + MAX_WBITS: a gzip header and trailer (CRC and size checked); MAX_WBITS alone: a zlib stream. */
    if (inflateInit2(&z, gzip ? 16 + MAX_WBITS : MAX_WBITS) != Z_OK)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: %s: cannot start zlib", name, what);
    fc_code code = inflate_all(&z, name, what, in, in_size, output_limit(in_size, expected_size), out, out_size, err);
    inflateEnd(&z);
    if (code == FC_OK && expected_size != 0 && *out_size != expected_size)
        code = fc_error_set(err, FC_ERR_PARSE, "%s: %s: inflates to %zu bytes, the header says %zu", name, what,
                            *out_size, expected_size);
    if (code != FC_OK) {
        free(*out);
        *out = NULL;
        *out_size = 0;
    }
    return code;
}
