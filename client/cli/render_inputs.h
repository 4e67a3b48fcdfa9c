/* render_inputs.h — the particle files of `fluidcast render`, in order: a list
 * of names, shell-style globs (expanded with glob(3), each sorted with
 * numbers in names compared by value), one printf-style frame pattern
 * ("frame_%04d.ply"): frames from --start (default: the lowest number that
 * exists) up by --step to --end (default: up to the first number missing), or
 * one "{}" pattern ("ParticleData_Fluid_{}.bgeo", render_brace.h): every file
 * with digits there, by number, those in --start..--end, every --step-th
 * counted from --start (default: the lowest). */
#ifndef FC_RENDER_INPUTS_H
#define FC_RENDER_INPUTS_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_frame_range {
    bool has_start, has_end;
    uint32_t start, end, step;    /* step >= 1 */
} fc_frame_range;

typedef struct fc_render_inputs {
    char **paths;                 /* count malloc'd names */
    uint32_t count;
    /* The frame number of each path: the pattern's numbers, otherwise 0, 1, ... */
    uint32_t *numbers;
} fc_render_inputs;

/* Whether `text` holds one %d conversion (%d, %4d, %04d; "%%" is a literal %)
 * and nothing else with a %. */
bool fc_is_frame_pattern(const char *text);

/* `text` with `number` put into its %d. FC_ERR_USAGE when it does not fit. */
fc_code fc_pattern_path(const char *pattern, uint32_t number, char *out, size_t size, fc_error *err);

/* Expands the INPUTS. FC_ERR_USAGE for a pattern among other inputs, a range
 * without a pattern, a glob that matches nothing, a pattern with no frame at
 * all (or none in the range), two files of one number in a {} pattern, or an
 * empty result; FC_ERR_NOMEM. Files named one by one (and with
 * --end, the pattern's) are not checked here: a missing one is reported when
 * its turn comes. Free with fc_render_inputs_free. */
fc_code fc_render_inputs_expand(const char *const *args, uint32_t arg_count, const fc_frame_range *range,
                                fc_render_inputs *out, fc_error *err);
void fc_render_inputs_free(fc_render_inputs *in);

#endif
