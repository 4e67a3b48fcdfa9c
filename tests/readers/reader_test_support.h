/* reader_test_support.h — what the reader tests share: building particle files
 * byte by byte (explicit byte order, so the expected values never come from the
 * code under test), temporary files, and sweeps that feed broken variants of a
 * good file (every truncation, random byte mutations) to the readers. */
#ifndef FC_READER_TEST_SUPPORT_H
#define FC_READER_TEST_SUPPORT_H

#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "fc_frame.h"
#include "particle_reader.h"
#include "test_util.h"

/* ---- building files ---- */

typedef struct bytes {
    uint8_t *data;
    size_t len;
    size_t cap;
} bytes;

static inline void bytes_append(bytes *b, const void *p, size_t n)
{
    if (b->len + n > b->cap) {
        size_t cap = b->cap ? b->cap : 256;
        while (cap < b->len + n)
            cap *= 2;
        uint8_t *grown = realloc(b->data, cap);
        if (grown == NULL) {
            fprintf(stderr, "out of memory building a test file\n");
            exit(2);
        }
        b->data = grown;
        b->cap = cap;
    }
    if (n)
        memcpy(b->data + b->len, p, n);
    b->len += n;
}

static inline void bytes_printf(bytes *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static inline void bytes_printf(bytes *b, const char *fmt, ...)
{
    char text[4096];
    va_list args;
    va_start(args, fmt);
    int n = vsnprintf(text, sizeof text, fmt, args);
    va_end(args);
    bytes_append(b, text, (size_t)n);
}

static inline void bytes_uint(bytes *b, uint64_t value, size_t size, bool big_endian)
{
    for (size_t i = 0; i < size; i++) {
        size_t shift = 8 * (big_endian ? size - 1 - i : i);
        uint8_t byte = (uint8_t)(value >> shift);
        bytes_append(b, &byte, 1);
    }
}

static inline void bytes_f32(bytes *b, float value, bool big_endian)
{
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    bytes_uint(b, bits, 4, big_endian);
}

static inline void bytes_f64(bytes *b, double value, bool big_endian)
{
    uint64_t bits;
    memcpy(&bits, &value, sizeof bits);
    bytes_uint(b, bits, 8, big_endian);
}

static inline void bytes_free(bytes *b)
{
    free(b->data);
    *b = (bytes){ NULL, 0, 0 };
}

/* ---- temporary files ---- */

static char temp_dir_[64];

static inline const char *temp_dir(void)
{
    if (temp_dir_[0] == '\0') {
        strcpy(temp_dir_, "/tmp/fc_readers_XXXXXX");
        if (mkdtemp(temp_dir_) == NULL) {
            perror("mkdtemp");
            exit(2);
        }
    }
    return temp_dir_;
}

/* Writes b to <temp dir>/<name> and returns that path (static storage, one at a time). */
static inline const char *write_temp_file(const char *name, const bytes *b)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", temp_dir(), name);
    FILE *file = fopen(path, "wb");
    if (file == NULL || (b->len && fwrite(b->data, 1, b->len, file) != b->len) || fclose(file) != 0) {
        perror(path);
        exit(2);
    }
    return path;
}

static inline void remove_temp_file(const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", temp_dir(), name);
    unlink(path);
}

static inline void remove_temp_dir(void)
{
    if (temp_dir_[0] != '\0')
        rmdir(temp_dir_);
}

/* ---- checks ---- */

static inline bool frame_is_empty(const fc_frame *f)
{
    return f->count == 0 && !f->positions && !f->density && !f->velocity && !f->ids;
}

static inline void check_position(const fc_frame *f, uint64_t i, float x, float y, float z)
{
    CHECK_MSG(f->positions[3 * i] == x && f->positions[3 * i + 1] == y && f->positions[3 * i + 2] == z,
              "particle %llu at (%g %g %g), expected (%g %g %g)", (unsigned long long)i, f->positions[3 * i],
              f->positions[3 * i + 1], f->positions[3 * i + 2], x, y, z);
}

static inline void check_velocity(const fc_frame *f, uint64_t i, float x, float y, float z)
{
    CHECK_MSG(f->velocity[3 * i] == x && f->velocity[3 * i + 1] == y && f->velocity[3 * i + 2] == z,
              "particle %llu velocity (%g %g %g), expected (%g %g %g)", (unsigned long long)i, f->velocity[3 * i],
              f->velocity[3 * i + 1], f->velocity[3 * i + 2], x, y, z);
}

/* Reads b as `name` expecting `code`; the message must name the file and, when
 * given, contain `needle`; no frame may come back. Returns the message. */
static inline const char *expect_failure(const bytes *b, fc_file_format format, const char *name, fc_code code,
                                  const char *needle)
{
    static fc_error err;
    fc_frame frame;
    memset(&err, 0, sizeof err);
    CHECK_CODE(fc_read_particles_mem(b->data, b->len, format, name, &frame, &err), code);
    CHECK_MSG(strstr(err.message, name) == err.message, "message '%s' does not start with '%s'", err.message, name);
    if (needle)
        CHECK_MSG(strstr(err.message, needle) != NULL, "message '%s' lacks '%s'", err.message, needle);
    CHECK(frame_is_empty(&frame));
    fc_frame_free(&frame);
    return err.message;
}

/* Same for a file given as text. */
static inline const char *expect_text_failure(const char *text, fc_file_format format, const char *name, const char *needle)
{
    bytes b = { NULL, 0, 0 };
    bytes_append(&b, text, strlen(text));
    const char *message = expect_failure(&b, format, name, FC_ERR_PARSE, needle);
    bytes_free(&b);
    return message;
}

static inline bool frame_is_consistent(const fc_frame *f)
{
    if (f->count == 0 || f->positions == NULL)
        return false;
    for (uint64_t i = 0; i < 3 * f->count; i++) {
        if (!isfinite(f->positions[i]) || (f->velocity && !isfinite(f->velocity[i])))
            return false;
    }
    for (uint64_t i = 0; f->density && i < f->count; i++) {
        if (!isfinite(f->density[i]))
            return false;
    }
    return true;
}

/* Every prefix of the good file b shorter than must_fail_below bytes must be
 * rejected with FC_ERR_PARSE naming the file; longer prefixes may parse (text
 * formats: a cut inside the last number still leaves a number) but must then
 * give a complete frame of at most max_count particles. */
static inline void check_truncations(const bytes *b, fc_file_format format, size_t must_fail_below, uint64_t max_count)
{
    int failures_before = test_failures_;
    for (size_t len = 0; len < b->len && test_failures_ == failures_before; len++) {
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        fc_code code = fc_read_particles_mem(len ? b->data : NULL, len, format, "cut.dat", &frame, &err);
        if (len < must_fail_below || code != FC_OK) {
            CHECK_MSG(code == FC_ERR_PARSE && strncmp(err.message, "cut.dat: ", 9) == 0,
                      "prefix of %zu bytes: code %d, message '%s'", len, (int)code, err.message);
            CHECK_MSG(frame_is_empty(&frame), "prefix of %zu bytes left a partial frame", len);
        } else {
            CHECK_MSG(frame_is_consistent(&frame) && frame.count <= max_count,
                      "prefix of %zu bytes gave %llu particles", len, (unsigned long long)frame.count);
        }
        fc_frame_free(&frame);
    }
}

/* Random single- and multi-byte corruptions of b: each read must either succeed
 * with a consistent frame or fail with FC_ERR_PARSE and no frame (the sanitizer
 * build turns any out-of-bounds access into a failure). */
static inline void check_mutations(const bytes *b, fc_file_format format, unsigned iterations, uint32_t seed)
{
    static const uint8_t interesting[] = { '\n', ' ', '0', '9', '-', '.', 'e', ',', '#', 0x00, 0x7f, 0x80, 0xff };
    uint8_t *copy = malloc(b->len);
    uint32_t state = seed;
    int failures_before = test_failures_;
    for (unsigned it = 0; it < iterations && test_failures_ == failures_before; it++) {
        memcpy(copy, b->data, b->len);
        unsigned edits = 1 + it % 4;
        for (unsigned e = 0; e < edits; e++) {
            state = state * 1664525u + 1013904223u;
            size_t at = (state >> 8) % b->len;
            state = state * 1664525u + 1013904223u;
            copy[at] = (state & 0x100) ? (uint8_t)(state >> 16) : interesting[(state >> 16) % sizeof interesting];
        }
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        fc_code code = fc_read_particles_mem(copy, b->len, format, "mutated.dat", &frame, &err);
        if (code == FC_OK)
            CHECK_MSG(frame_is_consistent(&frame), "mutation %u: inconsistent frame", it);
        else
            CHECK_MSG(code == FC_ERR_PARSE && strncmp(err.message, "mutated.dat: ", 13) == 0 &&
                          frame_is_empty(&frame),
                      "mutation %u: code %d, message '%s'", it, (int)code, err.message);
        fc_frame_free(&frame);
    }
    free(copy);
}

#endif
