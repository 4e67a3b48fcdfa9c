/* stage_timer.c — GL_TIME_ELAPSED queries per pipeline stage. */
#include "stage_timer.h"

#include "gl_util.h"

fc_code fc_stage_timer_create(fc_stage_timer *t, fc_error *err)
{
    *t = (fc_stage_timer){0};
    glCreateQueries(GL_TIME_ELAPSED, FC_STAGE_COUNT, t->queries);
    return fc_gl_check("creating timer queries", err);
}

void fc_stage_timer_destroy(fc_stage_timer *t)
{
    glDeleteQueries(FC_STAGE_COUNT, t->queries);
    *t = (fc_stage_timer){0};
}

void fc_stage_timer_reset(fc_stage_timer *t)
{
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        t->timed[s] = false;
}

void fc_stage_timer_begin(fc_stage_timer *t, fc_stage stage)
{
    glBeginQuery(GL_TIME_ELAPSED, t->queries[stage]);
}

void fc_stage_timer_end(fc_stage_timer *t, fc_stage stage)
{
    glEndQuery(GL_TIME_ELAPSED);
    t->timed[stage] = true;
}

float fc_stage_timer_ms(const fc_stage_timer *t, fc_stage stage)
{
    if (!t->timed[stage])
        return -1.0f;
    GLuint64 nanoseconds = 0;
    glGetQueryObjectui64v(t->queries[stage], GL_QUERY_RESULT, &nanoseconds);
    return (float)((double)nanoseconds * 1e-6);
}
