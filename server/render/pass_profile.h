/* pass_profile.h — an optional profile of one render, pass by pass, for the
 * benchmark: each pass's wall time with the GL queue drained before and after
 * it (on a software rasterizer that is the pass's own CPU time; on a GPU it
 * adds the drain's latency), the process's CPU time over it, and the fragment shader invocations it ran
 * (ARB_pipeline_statistics_query; -1 where the driver lacks it). Draining
 * serialises the passes, so a profiled render is slower than a plain one;
 * disabled, begin and end do nothing. */
#ifndef FC_PASS_PROFILE_H
#define FC_PASS_PROFILE_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "pipeline.h"

#define FC_PASS_PROFILE_MAX 32

typedef struct fc_pass_profile {
    bool enabled;
    bool has_statistics;      /* fragment counts available */
    GLuint fragment_query;
    double started_ms;
    double started_cpu_ms;
    int count;
    fc_pass_sample samples[FC_PASS_PROFILE_MAX];
} fc_pass_profile;

fc_code fc_pass_profile_create(fc_pass_profile *p, fc_error *err);
void fc_pass_profile_destroy(fc_pass_profile *p);

/* Forgets the passes of the last render. */
void fc_pass_profile_reset(fc_pass_profile *p);

/* Brackets one pass (name: a string literal); passes must not nest. Passes
 * beyond FC_PASS_PROFILE_MAX in one render are not recorded; a NULL profile
 * records nothing. */
void fc_pass_profile_begin(fc_pass_profile *p, const char *name);
void fc_pass_profile_end(fc_pass_profile *p);

#endif
