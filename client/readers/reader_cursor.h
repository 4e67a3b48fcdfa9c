/* reader_cursor.h — internal to the particle readers: a bounded cursor over a
 * file held in memory, text spans and tokens, binary scalar decoding, and
 * error messages that name the file and the place ("frame.ply: line 12: ...").
 *
 * Nothing here reads past `size`: every access goes through a length check, so
 * the format readers can treat any byte sequence as untrusted input. */
#ifndef FC_READER_CURSOR_H
#define FC_READER_CURSOR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "fluidcast_types.h"

/* A read-only slice of text; not NUL-terminated. */
typedef struct fc_span {
    const char *ptr;
    size_t len;
} fc_span;

typedef struct fc_cursor {
    const uint8_t *data;
    size_t size;
    size_t pos;
    size_t line_at_pos;   /* 1-based line number of data[pos] */
    size_t line;          /* line of the last line or token returned: what errors report */
    bool binary;          /* errors report the byte offset: line numbers mean nothing in binary data */
    const char *name;     /* file name for messages */
    const struct fc_read_options *options; /* the read's options (particle_reader.h), set for every format reader */
    struct fc_read_extras *extras;  /* where a reader keeps named scalars for --select; NULL: keep none */
    struct fc_positions64 *positions64; /* where float64 positions wait for the recentring; NULL: none */
    uint8_t *adoptable;   /* data itself when it is a malloc'd buffer a reader may keep as a frame's array
                             (reader_f32.c), set to NULL once kept; NULL: readers copy */
} fc_cursor;

void fc_cursor_init(fc_cursor *c, const uint8_t *data, size_t size, const char *name);
size_t fc_cursor_remaining(const fc_cursor *c);

/* FC_ERR_PARSE with "name: line N: <reason>" (or "name: byte offset N: <reason>"
 * in binary mode). */
fc_code fc_cursor_fail(const fc_cursor *c, fc_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ---- text ---- */

/* The next line without its "\n" or "\r\n"; false at the end of the data. */
bool fc_cursor_next_line(fc_cursor *c, fc_span *line);
/* The next line that is not blank (only spaces, tabs, CR); false at the end. */
bool fc_cursor_next_nonblank_line(fc_cursor *c, fc_span *line);
/* The next whitespace-separated token, across lines; false at the end. */
bool fc_cursor_next_token(fc_cursor *c, fc_span *token);
/* Whether the next token (binary mode: the bytes at pos, without skipping
 * whitespace) is `keyword`, case-insensitively. Does not move the cursor. */
bool fc_cursor_peek_keyword(const fc_cursor *c, const char *keyword);

fc_span fc_span_trim(fc_span s);
bool fc_span_is_blank(fc_span s);
bool fc_span_iequals(fc_span s, const char *word);
bool fc_span_istarts_with(fc_span s, const char *prefix);
/* Splits off the next whitespace-separated token of *rest; false when none is left. */
bool fc_span_next_token(fc_span *rest, fc_span *token);
size_t fc_span_count_tokens(fc_span s);
/* Splits off the text up to the next `separator` (or the end); false once *rest is used up. */
bool fc_span_next_field(fc_span *rest, char separator, fc_span *field);
/* The whole span as a number (strtod syntax). Non-finite results are left to the caller. */
bool fc_span_to_double(fc_span s, double *out);
/* The whole span as a non-negative decimal integer. */
bool fc_span_to_count(fc_span s, uint64_t *out);
/* Copies at most bufsize-1 characters of s into buf for a message, with
 * non-printable bytes shown as '?' and "..." when cut. */
const char *fc_span_quote(fc_span s, char *buf, size_t bufsize);
#define FC_QUOTE_MAX 48

/* ---- binary ---- */

typedef enum fc_scalar_type {
    FC_SCALAR_I8,
    FC_SCALAR_U8,
    FC_SCALAR_I16,
    FC_SCALAR_U16,
    FC_SCALAR_I32,
    FC_SCALAR_U32,
    FC_SCALAR_I64,
    FC_SCALAR_U64,
    FC_SCALAR_F32,
    FC_SCALAR_F64
} fc_scalar_type;

size_t fc_scalar_size(fc_scalar_type type);

/* Reads one scalar stored with the given byte order and widens it to double;
 * false (cursor unmoved) when fewer than its size bytes remain. */
bool fc_cursor_read_scalar(fc_cursor *c, fc_scalar_type type, bool big_endian, double *out);
/* Skips count items of item_size bytes; false (cursor unmoved) when they do not fit. */
bool fc_cursor_skip_items(fc_cursor *c, uint64_t count, size_t item_size);

#endif
