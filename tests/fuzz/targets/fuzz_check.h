/* fuzz_check.h — invariants the fuzz targets assert beyond "no sanitizer report".
 * A broken invariant aborts, which libFuzzer records as a crash with the input
 * that caused it. */
#ifndef FC_FUZZ_CHECK_H
#define FC_FUZZ_CHECK_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fluidcast_types.h"

#define FUZZ_REQUIRE(cond, ...)                                                        \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            fprintf(stderr, "%s:%d: fuzz invariant failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                              \
            fputc('\n', stderr);                                                       \
            abort();                                                                   \
        }                                                                              \
    } while (0)

/* Errors are values: a refusal must come with the same code in *err and a reason. */
static inline void fuzz_require_reported(fc_code code, const fc_error *err)
{
    FUZZ_REQUIRE(code != FC_OK, "expected a refusal");
    FUZZ_REQUIRE(err->code == code, "returned code %d but err->code %d", (int)code, (int)err->code);
    FUZZ_REQUIRE(err->message[0] != '\0', "code %d without a message", (int)code);
    FUZZ_REQUIRE(memchr(err->message, '\0', sizeof err->message) != NULL, "message not terminated");
}

/* A text field a decoder filled must be terminated inside its array. */
static inline void fuzz_require_terminated(const char *text, size_t capacity)
{
    FUZZ_REQUIRE(memchr(text, '\0', capacity) != NULL, "string of capacity %zu not terminated", capacity);
}

#endif
