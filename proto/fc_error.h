/* fc_error.h — building and naming error values (see fc_error in fluidcast_types.h). */
#ifndef FC_ERROR_H
#define FC_ERROR_H

#include "fc_api.h"
#include "fluidcast_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fills *err (when err is non-NULL) with code and a printf-style message, and
 * returns code, so failures read `return fc_error_set(err, FC_ERR_IO, "...", ...);`. */
FC_API fc_code fc_error_set(fc_error *err, fc_code code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Resets *err to FC_OK with an empty message. */
FC_API void fc_error_clear(fc_error *err);

/* Stable lower-case name of a code, e.g. "malformed" for FC_ERR_MALFORMED; "unknown" otherwise. */
FC_API const char *fc_code_name(fc_code code);

#ifdef __cplusplus
}
#endif
#endif
