/* cli_values.h — parsing option values ("1280x720", "1,2,3", "0.5", "40") with
 * the whole text checked: trailing garbage, overflow and non-finite numbers are
 * FC_ERR_USAGE naming the option. */
#ifndef FC_CLI_VALUES_H
#define FC_CLI_VALUES_H

#include <stdint.h>
#include "fluidcast_types.h"

/* A finite float. */
fc_code fc_cli_parse_float(const char *option, const char *text, float *out, fc_error *err);

/* An unsigned integer in [min, max]. */
fc_code fc_cli_parse_uint(const char *option, const char *text, uint32_t min, uint32_t max,
                          uint32_t *out, fc_error *err);

/* "X,Y,Z": three finite floats. */
fc_code fc_cli_parse_vec3(const char *option, const char *text, float out[3], fc_error *err);

/* An up direction: "x", "y", "z", "-x", "-y", "-z" (also "+x" ...) for the
 * unit vectors, or "X,Y,Z". */
fc_code fc_cli_parse_up(const char *option, const char *text, float out[3], fc_error *err);

/* "WxH": two integers >= 1. */
fc_code fc_cli_parse_size(const char *option, const char *text, uint32_t *width, uint32_t *height,
                          fc_error *err);

/* The index of `text` in the NULL-terminated `choices`. */
fc_code fc_cli_parse_choice(const char *option, const char *text, const char *const *choices,
                            int *out, fc_error *err);

#endif
