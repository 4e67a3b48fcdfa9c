/* png_strips.h — the zlib stream of a PNG's image data, deflated in
 * horizontal strips of rows on several threads (pigz's technique).
 *
 * Each strip's rows are filtered (SUB, or none at level 0) and deflated by
 * zlib as raw deflate with the 32 KiB of filtered bytes before the strip as
 * its dictionary, so it compresses as well as one stream would. Every strip
 * but the last ends with a sync flush (byte-aligned, not final), the last with
 * the stream's final block: the strips concatenated, between a zlib header
 * and the adler32 of all filtered bytes, are one valid zlib stream.
 *
 * Strips are a fixed number of filtered bytes (FC_PNG_STRIP_BYTES, at least one
 * row), so the output is the same whatever the thread count. */
#ifndef FC_PNG_STRIPS_H
#define FC_PNG_STRIPS_H

#include <stddef.h>
#include <stdint.h>

#include "fc_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Filtered bytes per strip. 128 KiB: on a 1024x768 RGBA image 25 strips,
 * enough to keep 8 threads evenly busy; with the dictionary, the file is as
 * large as one stream's (bench/RESULTS.md). */
#define FC_PNG_STRIP_BYTES (128u * 1024u)
/* The most threads one image is split over (automatic choice). */
#define FC_PNG_MAX_THREADS 8u

/* 8-bit rows, top to bottom, no padding: `channels` bytes per pixel written,
 * read `stride` bytes apart (0: `channels`; more: the pixel's first `channels`
 * bytes are written, the rest left out, e.g. an RGBA image's opaque alpha). */
typedef struct fc_png_rows {
    const uint8_t *pixels;
    uint32_t width;
    uint32_t height;
    uint32_t channels;
    uint32_t stride;
} fc_png_rows;

typedef struct fc_png_strip {
    uint8_t *data;       /* raw deflate bytes */
    size_t len;
    uint32_t adler;      /* adler32 of the strip's filtered bytes */
    size_t filtered_len; /* how many filtered bytes the strip holds */
} fc_png_strip;

typedef struct fc_png_strips {
    fc_png_strip *strip;
    uint32_t count;
} fc_png_strips;

/* Filters and deflates `rows` at zlib `level` (0..9) on up to `threads`
 * threads (0: fc_png_default_threads(); never more
 * than there are strips). The calling thread works too; if a thread cannot be
 * started, the others do its share. FC_ERR_NOMEM, or FC_ERR_ENCODE with
 * zlib's code; out is empty then. */
fc_code fc_png_deflate_strips(const fc_png_rows *rows, uint32_t level, unsigned threads, fc_png_strips *out,
                              fc_error *err);

/* The adler32 of the whole filtered stream: the strips' combined. */
uint32_t fc_png_strips_adler(const fc_png_strips *strips);

void fc_png_strips_free(fc_png_strips *strips);

/* One per core this process may use (its affinity mask: Slurm, containers,
 * taskset), at most FC_PNG_MAX_THREADS, at least 1. */
unsigned fc_png_default_threads(void);

#ifdef __cplusplus
}
#endif
#endif
