/* png_strips.c — see png_strips.h. */
#include "png_strips.h"

#include <limits.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "fc_parallel.h"

/* PNG row filter types (PNG spec 9.2). */
enum { FILTER_NONE = 0, FILTER_SUB = 1 };
/* deflate's window: the dictionary a strip starts with. */
enum { WINDOW_BYTES = 32768 };
/* zlib counts in uInt: feed it at most this much at a time. */
#define ZLIB_CHUNK ((size_t)1 << 30)

/* One encode's shared state: strips are handed out by `next`; each strip's
 * result is written by the one thread that took it. */
typedef struct strip_work {
    const fc_png_rows *rows;
    int level;
    size_t row_bytes;    /* filtered: filter type byte + the row */
    uint32_t strip_rows;
    uint32_t dict_rows;  /* rows before a strip that cover the window */
    fc_png_strips *strips;
    int *zlib_code;      /* per strip: Z_OK, or what failed */
    atomic_uint next;
} strip_work;

unsigned fc_png_default_threads(void)
{
    unsigned cores = fc_usable_cores();
    return cores < FC_PNG_MAX_THREADS ? cores : FC_PNG_MAX_THREADS;
}

/* The bytes between two pixels of the source rows. */
static uint32_t pixel_stride(const fc_png_rows *r)
{
    return r->stride > r->channels ? r->stride : r->channels;
}

/* One filtered row: the type byte, then the samples (SUB: each minus the
 * same channel of the pixel to its left, PNG spec 9.2). */
static void filter_row(const uint8_t *row, size_t bytes, uint32_t bpp, int filter, uint8_t *out)
{
    out[0] = (uint8_t)filter;
    out++;
    if (filter == FILTER_NONE) {
        memcpy(out, row, bytes);
        return;
    }
    size_t lead = bytes < bpp ? bytes : bpp;
    memcpy(out, row, lead);
    for (size_t i = lead; i < bytes; i++)
        out[i] = (uint8_t)(row[i] - row[i - bpp]);
}

/* The same for source pixels `stride` bytes apart, of which the first
 * `bpp` are written (an RGBA row written as RGB). */
static void filter_strided_row(const uint8_t *row, uint32_t width, uint32_t bpp, uint32_t stride, int filter,
                               uint8_t *out)
{
    static const uint8_t black[4] = {0};
    *out++ = (uint8_t)filter;
    const uint8_t *left = black;   /* SUB's pixel to the left; none for the first, or without a filter */
    for (uint32_t x = 0; x < width; x++, row += stride, out += bpp) {
        for (uint32_t c = 0; c < bpp; c++)
            out[c] = (uint8_t)(row[c] - left[c]);
        if (filter == FILTER_SUB)
            left = row;
    }
}

static void filter_rows(const strip_work *w, uint32_t first, uint32_t end, uint8_t *out)
{
    const fc_png_rows *r = w->rows;
    uint32_t stride = pixel_stride(r);
    size_t source_bytes = (size_t)r->width * stride;
    int filter = w->level == 0 ? FILTER_NONE : FILTER_SUB;
    for (uint32_t y = first; y < end; y++, out += w->row_bytes) {
        const uint8_t *row = r->pixels + (size_t)y * source_bytes;
        if (stride == r->channels)
            filter_row(row, w->row_bytes - 1, r->channels, filter, out);
        else
            filter_strided_row(row, r->width, r->channels, stride, filter, out);
    }
}

/* Makes room for at least `want` more output bytes (doubling). */
static bool grow(fc_png_strip *s, size_t *cap, size_t want)
{
    if (*cap - s->len >= want)
        return true;
    size_t bigger = *cap * 2 > s->len + want ? *cap * 2 : s->len + want;
    uint8_t *data = realloc(s->data, bigger);
    if (!data)
        return false;
    s->data = data;
    *cap = bigger;
    return true;
}

/* Deflates `n` bytes with `flush` at their end (Z_SYNC_FLUSH or Z_FINISH)
 * into s->data. Returns Z_OK, Z_MEM_ERROR or zlib's error. */
static int deflate_into(z_stream *z, const uint8_t *in, size_t n, int flush, fc_png_strip *s)
{
    /* The bound, plus room for the flush marker (zlib asks for more than 6). */
    size_t cap = deflateBound(z, n) + 64;
    s->data = malloc(cap);
    if (!s->data)
        return Z_MEM_ERROR;
    size_t done = 0;
    for (;;) {
        if (!grow(s, &cap, 64))
            return Z_MEM_ERROR;
        size_t in_now = n - done < ZLIB_CHUNK ? n - done : ZLIB_CHUNK;
        size_t room = cap - s->len < ZLIB_CHUNK ? cap - s->len : ZLIB_CHUNK;
        bool last = done + in_now == n;
        z->next_in = (Bytef *)(uintptr_t)(in + done); /* zlib's API is not const */
        z->avail_in = (uInt)in_now;
        z->next_out = s->data + s->len;
        z->avail_out = (uInt)room;
        int rc = deflate(z, last ? flush : Z_NO_FLUSH);
        done += in_now - z->avail_in;
        s->len += room - z->avail_out;
        if (rc == Z_STREAM_ERROR)
            return rc;
        /* Done when all input is in and the flush completed: Z_STREAM_END for
         * Z_FINISH, output space left over for Z_SYNC_FLUSH (zlib's manual). */
        if (done == n && last && (flush == Z_FINISH ? rc == Z_STREAM_END : z->avail_out != 0))
            return Z_OK;
    }
}

/* Filters strip k (after the rows its dictionary needs) into `filtered` and deflates it. */
static int deflate_strip(strip_work *w, uint32_t k, z_stream *z, uint8_t *filtered)
{
    uint32_t first = k * w->strip_rows;
    uint32_t end = first + w->strip_rows < w->rows->height ? first + w->strip_rows : w->rows->height;
    /* The rows before the strip, as far back as the window reaches; level 0
     * stores, so it has no matches to find and needs no dictionary. */
    uint32_t dict_first = first;
    if (w->level > 0)
        dict_first = first > w->dict_rows ? first - w->dict_rows : 0;
    filter_rows(w, dict_first, end, filtered);
    size_t dict_len = (size_t)(first - dict_first) * w->row_bytes;
    size_t n = (size_t)(end - first) * w->row_bytes;
    fc_png_strip *s = &w->strips->strip[k];
    int rc = deflateReset(z);
    if (rc == Z_OK && dict_len > 0) {
        size_t use = dict_len < WINDOW_BYTES ? dict_len : WINDOW_BYTES;
        rc = deflateSetDictionary(z, filtered + dict_len - use, (uInt)use);
    }
    if (rc != Z_OK)
        return rc;
    bool final = k + 1 == w->strips->count;
    rc = deflate_into(z, filtered + dict_len, n, final ? Z_FINISH : Z_SYNC_FLUSH, s);
    /* adler32 takes uInt lengths: adler32_z takes size_t. */
    s->adler = (uint32_t)adler32_z(1, filtered + dict_len, n);
    s->filtered_len = n;
    return rc;
}

/* Takes strips until none is left; one z_stream and filter buffer per thread.
 * A thread that starts after the others took every strip leaves at once,
 * before allocating anything (on a loaded machine helpers start late). */
static void *strip_worker(void *arg)
{
    strip_work *w = arg;
    unsigned k = atomic_fetch_add(&w->next, 1);
    if (k >= w->strips->count)
        return NULL;
    z_stream z;
    memset(&z, 0, sizeof z);
    /* Raw deflate (negative window bits): the PNG writer adds zlib's header
     * and adler32 around all strips. memLevel 8 and the default strategy:
     * what libpng uses for filtered rows at these levels. */
    int init = deflateInit2(&z, w->level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY);
    uint8_t *filtered = malloc((size_t)(w->strip_rows + w->dict_rows) * w->row_bytes);
    do {
        if (init != Z_OK)
            w->zlib_code[k] = init;
        else if (!filtered)
            w->zlib_code[k] = Z_MEM_ERROR;
        else
            w->zlib_code[k] = deflate_strip(w, k, &z, filtered);
    } while ((k = atomic_fetch_add(&w->next, 1)) < w->strips->count);
    free(filtered);
    if (init == Z_OK)
        deflateEnd(&z);
    return NULL;
}

/* Runs strip_worker on the calling thread and up to threads - 1 more. */
static void run_workers(strip_work *w, unsigned threads)
{
    pthread_t helper[FC_PNG_MAX_THREADS];
    unsigned started = 0;
    if (threads > FC_PNG_MAX_THREADS)
        threads = FC_PNG_MAX_THREADS;
    /* A thread that cannot start leaves its share to the others. */
    while (started + 1 < threads && pthread_create(&helper[started], NULL, strip_worker, w) == 0)
        started++;
    strip_worker(w);
    for (unsigned i = 0; i < started; i++)
        pthread_join(helper[i], NULL);
}

static fc_code strip_failure(const int *zlib_code, uint32_t count, fc_error *err)
{
    for (uint32_t k = 0; k < count; k++) {
        if (zlib_code[k] == Z_MEM_ERROR)
            return fc_error_set(err, FC_ERR_NOMEM, "PNG: out of memory deflating strip %u", k);
        if (zlib_code[k] != Z_OK)
            return fc_error_set(err, FC_ERR_ENCODE, "PNG: zlib error %d deflating strip %u", zlib_code[k], k);
    }
    return FC_OK;
}

fc_code fc_png_deflate_strips(const fc_png_rows *rows, uint32_t level, unsigned threads, fc_png_strips *out,
                              fc_error *err)
{
    memset(out, 0, sizeof *out);
    if (level > 9)
        return fc_error_set(err, FC_ERR_USAGE, "PNG: compression %u outside 0..9", level);
    if (!rows->pixels || rows->width == 0 || rows->height == 0 || rows->channels == 0 || rows->channels > 4 ||
        (rows->stride != 0 && (rows->stride < rows->channels || rows->stride > 4)))
        return fc_error_set(err, FC_ERR_USAGE, "PNG: empty image, or %u channels %u bytes apart", rows->channels,
                            rows->stride);
    strip_work w = {.rows = rows, .level = (int)level};
    w.row_bytes = (size_t)rows->width * rows->channels + 1;
    size_t per_strip = FC_PNG_STRIP_BYTES / w.row_bytes;
    w.strip_rows = per_strip == 0 ? 1 : per_strip > rows->height ? rows->height : (uint32_t)per_strip;
    w.dict_rows = (uint32_t)((WINDOW_BYTES + w.row_bytes - 1) / w.row_bytes);
    uint32_t count = rows->height / w.strip_rows + (rows->height % w.strip_rows != 0);
    out->strip = calloc(count, sizeof *out->strip);
    w.zlib_code = calloc(count, sizeof *w.zlib_code);
    if (!out->strip || !w.zlib_code) {
        free(w.zlib_code);
        free(out->strip);
        out->strip = NULL;
        return fc_error_set(err, FC_ERR_NOMEM, "PNG: out of memory for %u strips", count);
    }
    out->count = count;
    w.strips = out;
    atomic_init(&w.next, 0);
    if (threads == 0)
        threads = fc_png_default_threads();
    run_workers(&w, threads < count ? threads : count);
    fc_code code = strip_failure(w.zlib_code, count, err);
    free(w.zlib_code);
    if (code != FC_OK)
        fc_png_strips_free(out);
    return code;
}

uint32_t fc_png_strips_adler(const fc_png_strips *strips)
{
    if (strips->count == 0)
        return (uint32_t)adler32(0L, Z_NULL, 0);
    uLong adler = strips->strip[0].adler;
    for (uint32_t k = 1; k < strips->count; k++)
        adler = adler32_combine(adler, strips->strip[k].adler, (z_off_t)strips->strip[k].filtered_len);
    return (uint32_t)adler;
}

void fc_png_strips_free(fc_png_strips *strips)
{
    for (uint32_t k = 0; strips->strip && k < strips->count; k++)
        free(strips->strip[k].data);
    free(strips->strip);
    strips->strip = NULL;
    strips->count = 0;
}
