/* png_encoder.c — see png_encoder.h. The chunk layout follows the PNG
 * specification (ISO/IEC 15948): 4.7 chunks, 11.2 IHDR, 12.6 oFFs (PNG
 * extensions), 10 the zlib stream (RFC 1950) that the IDATs carry. */
#include "png_encoder.h"

#include <stdbool.h>
#include <string.h>
#include <zlib.h>

/* PNG stores sizes and lengths as 31-bit numbers (spec 7.1). */
#define PNG_MAX_U31 0x7fffffffu

enum { COLOUR_GREY = 0, COLOUR_RGB = 2, COLOUR_RGBA = 6 };

static void put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

/* One chunk whose data is the pieces in order (a NULL piece is skipped);
 * the CRC covers the type and the data. Room was reserved by the caller. */
static void append_chunk(fc_buf *out, const char type[4], const uint8_t *const piece[], const size_t len[],
                         int pieces)
{
    size_t total = 0;
    for (int i = 0; i < pieces; i++)
        total += piece[i] ? len[i] : 0;
    uint8_t *p = out->data + out->len;
    put_u32(p, (uint32_t)total);
    memcpy(p + 4, type, 4);
    uLong crc = crc32_z(crc32(0L, Z_NULL, 0), p + 4, 4);
    p += 8;
    for (int i = 0; i < pieces; i++) {
        if (!piece[i] || len[i] == 0)
            continue;
        memcpy(p, piece[i], len[i]);
        crc = crc32_z(crc, p, len[i]);
        p += len[i];
    }
    put_u32(p, (uint32_t)crc);
    out->len += 12 + total;
}

static void append_simple_chunk(fc_buf *out, const char type[4], const uint8_t *data, size_t len)
{
    const uint8_t *piece[1] = {data};
    size_t lens[1] = {len};
    append_chunk(out, type, piece, lens, 1);
}

/* RFC 1950's two header bytes: deflate with a 32 KiB window, FLEVEL as zlib
 * itself would write it for `level`, and the check bits. */
static void zlib_header(uint32_t level, uint8_t header[2])
{
    unsigned flevel = level < 2 ? 0 : level < 6 ? 1 : level == 6 ? 2 : 3;
    unsigned cmf = 0x78, flg = flevel << 6;
    flg += 31 - ((cmf << 8) + flg) % 31;
    header[0] = (uint8_t)cmf;
    header[1] = (uint8_t)flg;
}

static void append_header_chunks(fc_buf *out, const fc_png_rows *rows)
{
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    memcpy(out->data + out->len, signature, sizeof signature);
    out->len += sizeof signature;
    uint8_t ihdr[13] = {0};
    put_u32(ihdr, rows->width);
    put_u32(ihdr + 4, rows->height);
    ihdr[8] = 8; /* bits per sample; compression, filter method and interlace stay 0 */
    ihdr[9] = rows->channels == 1 ? COLOUR_GREY : rows->channels == 3 ? COLOUR_RGB : COLOUR_RGBA;
    append_simple_chunk(out, "IHDR", ihdr, sizeof ihdr);
    uint8_t offs[9] = {0}; /* x 0, y 0, unit: pixels */
    append_simple_chunk(out, "oFFs", offs, sizeof offs);
}

/* One IDAT per strip; the zlib header opens the first, the adler32 closes the last. */
static void append_idats(fc_buf *out, const fc_png_strips *strips, uint32_t level)
{
    uint8_t header[2], adler[4];
    zlib_header(level, header);
    put_u32(adler, fc_png_strips_adler(strips));
    for (uint32_t k = 0; k < strips->count; k++) {
        bool first = k == 0, last = k + 1 == strips->count;
        const uint8_t *piece[3] = {first ? header : NULL, strips->strip[k].data, last ? adler : NULL};
        size_t len[3] = {sizeof header, strips->strip[k].len, sizeof adler};
        append_chunk(out, "IDAT", piece, len, 3);
    }
}

static fc_code check_rows(const fc_png_rows *rows, uint32_t level, fc_error *err)
{
    if (!rows || !rows->pixels || rows->width == 0 || rows->height == 0)
        return fc_error_set(err, FC_ERR_USAGE, "PNG: empty image");
    if (rows->width > PNG_MAX_U31 || rows->height > PNG_MAX_U31)
        return fc_error_set(err, FC_ERR_USAGE, "PNG: %ux%u is larger than PNG's 2^31-1", rows->width,
                            rows->height);
    if (rows->channels != 1 && rows->channels != 3 && rows->channels != 4)
        return fc_error_set(err, FC_ERR_USAGE, "PNG: %u channels (expected 1, 3 or 4)", rows->channels);
    if (rows->stride != 0 && (rows->stride < rows->channels || rows->stride > 4))
        return fc_error_set(err, FC_ERR_USAGE, "PNG: %u channels read %u bytes apart", rows->channels, rows->stride);
    if (level > 9)
        return fc_error_set(err, FC_ERR_USAGE, "PNG: compression %u outside 0..9", level);
    return FC_OK;
}

fc_code fc_png_encode(const fc_png_rows *rows, uint32_t level, unsigned threads, fc_buf *out, fc_error *err)
{
    fc_code code = check_rows(rows, level, err);
    if (code != FC_OK)
        return code;
    fc_png_strips strips;
    code = fc_png_deflate_strips(rows, level, threads, &strips, err);
    if (code != FC_OK)
        return code;
    /* Signature, IHDR, oFFs, IEND, and per strip an IDAT's 12 bytes around its data. */
    size_t size = 8 + (12 + 13) + (12 + 9) + 12 + 2 + 4;
    for (uint32_t k = 0; k < strips.count; k++) {
        if (strips.strip[k].len > PNG_MAX_U31 - 6) {
            fc_png_strips_free(&strips);
            return fc_error_set(err, FC_ERR_ENCODE, "PNG: strip %u deflated to %zu bytes, more than a chunk holds",
                                k, strips.strip[k].len);
        }
        size += 12 + strips.strip[k].len;
    }
    if (!fc_buf_reserve(out, size)) {
        fc_png_strips_free(&strips);
        return fc_error_set(err, FC_ERR_NOMEM, "PNG: cannot grow the output buffer by %zu bytes", size);
    }
    append_header_chunks(out, rows);
    append_idats(out, &strips, level);
    append_simple_chunk(out, "IEND", NULL, 0);
    fc_png_strips_free(&strips);
    return FC_OK;
}
