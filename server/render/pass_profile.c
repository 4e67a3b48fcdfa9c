/* pass_profile.c — wall time and fragment counts of single passes. */
#include "pass_profile.h"

#include <time.h>

#include "gl_util.h"

static double clock_ms(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

fc_code fc_pass_profile_create(fc_pass_profile *p, fc_error *err)
{
    *p = (fc_pass_profile){0};
    p->has_statistics = epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query");
    if (p->has_statistics)
        glGenQueries(1, &p->fragment_query);
    return fc_gl_check("creating the pass profile's query", err);
}

void fc_pass_profile_destroy(fc_pass_profile *p)
{
    glDeleteQueries(1, &p->fragment_query);
    *p = (fc_pass_profile){0};
}

void fc_pass_profile_reset(fc_pass_profile *p)
{
    p->count = 0;
}

void fc_pass_profile_begin(fc_pass_profile *p, const char *name)
{
    if (!p || !p->enabled || p->count == FC_PASS_PROFILE_MAX)
        return;
    glFinish();
    p->samples[p->count] = (fc_pass_sample){.name = name, .fragments = -1};
    if (p->has_statistics)
        glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, p->fragment_query);
    p->started_ms = clock_ms(CLOCK_MONOTONIC);
    p->started_cpu_ms = clock_ms(CLOCK_PROCESS_CPUTIME_ID);
}

void fc_pass_profile_end(fc_pass_profile *p)
{
    if (!p || !p->enabled || p->count == FC_PASS_PROFILE_MAX)
        return;
    glFinish();
    fc_pass_sample *s = &p->samples[p->count++];
    s->ms = clock_ms(CLOCK_MONOTONIC) - p->started_ms;
    s->cpu_ms = clock_ms(CLOCK_PROCESS_CPUTIME_ID) - p->started_cpu_ms;
    if (!p->has_statistics)
        return;
    glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
    GLuint64 fragments = 0;
    glGetQueryObjectui64v(p->fragment_query, GL_QUERY_RESULT, &fragments);
    s->fragments = (int64_t)fragments;
}
