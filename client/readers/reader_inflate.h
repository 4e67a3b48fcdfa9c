/* reader_inflate.h — internal to the particle readers: zlib inflation of whole
 * gzip files (a .bgeo gzip'd under its own name) and of zlib blocks (VTK XML's
 * vtkZLibDataCompressor), with the output bounded so a hostile stream cannot
 * grow without end. */
#ifndef FC_READER_INFLATE_H
#define FC_READER_INFLATE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "fluidcast_types.h"

/* Whether data starts with gzip's magic bytes 1f 8b. */
bool fc_is_gzip(const uint8_t *data, size_t size);

/* Inflates in[0..in_size) — one gzip member when gzip is true, else one zlib
 * stream — into a malloc'd *out of *out_size bytes (free with free()).
 * expected_size: the exact size the output must have when the container states
 * it (a zlib block), or 0 when unknown: the output may then grow up to deflate's
 * largest ratio (1032:1). Bytes after the stream's end are refused.
 * Errors: FC_ERR_PARSE "name: what: ..." for corrupt or truncated data or a
 * wrong size, FC_ERR_NOMEM when the output cannot be allocated. */
fc_code fc_inflate(const char *name, const char *what, const uint8_t *in, size_t in_size, bool gzip,
                   size_t expected_size, uint8_t **out, size_t *out_size, fc_error *err);

#endif
