/* render_brace.h — a `{}` frame pattern of `fluidcast render`
 * ("output/partio/ParticleData_Fluid_{}.bgeo"): the "{}" stands for the
 * frame number written with any number of digits, padded or not, so that it
 * matches the names simulators write (SPlisHSPlasH counts 1, 2, ... 10
 * unpadded). The files are found with glob(3) and ordered by their numbers,
 * not by their names. */
#ifndef FC_RENDER_BRACE_H
#define FC_RENDER_BRACE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_brace_match {
    uint32_t number;   /* the value of the digits where "{}" stands */
    char *path;        /* malloc'd */
} fc_brace_match;

/* Whether `text` holds "{}" exactly once. */
bool fc_is_brace_pattern(const char *text);

/* The existing files the pattern matches (one or more decimal digits in
 * place of "{}", nothing else), by ascending number. FC_ERR_USAGE when none
 * matches or two files carry the same number (f_1 and f_01), FC_ERR_NOMEM,
 * FC_ERR_IO when the directory cannot be read. Free with fc_brace_matches_free. */
fc_code fc_brace_matches(const char *pattern, fc_brace_match **out, size_t *count, fc_error *err);
void fc_brace_matches_free(fc_brace_match *matches, size_t count);

#endif
