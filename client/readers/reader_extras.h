/* reader_extras.h — internal to the particle readers: named per-particle scalars
 * a file has beyond the frame's attributes (DualSPHysics' Type and Mk, PySPH's
 * tag, SWIFT's Masses, ...). They exist only for --select (reader_select.c) and
 * are never sent; a reader keeps them only when the cursor carries a table. */
#ifndef FC_READER_EXTRAS_H
#define FC_READER_EXTRAS_H

#include <stddef.h>
#include <stdint.h>
#include "fluidcast_types.h"
#include "reader_cursor.h"

enum { FC_EXTRAS_MAX = 32, FC_EXTRA_NAME_MAX = 64 };

typedef struct fc_read_extras {
    size_t size;
    char names[FC_EXTRAS_MAX][FC_EXTRA_NAME_MAX];
    double *values[FC_EXTRAS_MAX];   /* one value per particle of the frame */
} fc_read_extras;

/* Adds an array of count values (NaN until stored) named `name` and returns it; NULL with
 * *err set when memory runs out, NULL with FC_OK when the table is full, the name too long
 * or already taken (that column is then not selectable). */
double *fc_extras_add(fc_read_extras *x, fc_span name, uint64_t count, const char *file, fc_error *err,
                      fc_code *code);

/* The array named `name` (case-insensitive), or NULL. */
const double *fc_extras_find(const fc_read_extras *x, const char *name);

void fc_extras_free(fc_read_extras *x);

#endif
