/* stage_timer.h — GPU durations of the pipeline stages from GL_TIME_ELAPSED
 * queries, one query object per stage, timed one after another. */
#ifndef FC_STAGE_TIMER_H
#define FC_STAGE_TIMER_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "fluidcast_types.h"

typedef struct fc_stage_timer {
    GLuint queries[FC_STAGE_COUNT];
    bool timed[FC_STAGE_COUNT];   /* began and ended since the last reset */
} fc_stage_timer;

fc_code fc_stage_timer_create(fc_stage_timer *t, fc_error *err);
void fc_stage_timer_destroy(fc_stage_timer *t);

/* Forgets every stage timed so far. */
void fc_stage_timer_reset(fc_stage_timer *t);

/* Brackets the GL commands of one stage; stages must not overlap. */
void fc_stage_timer_begin(fc_stage_timer *t, fc_stage stage);
void fc_stage_timer_end(fc_stage_timer *t, fc_stage stage);

/* Milliseconds the GPU spent in `stage`, waiting for the result; -1 when the
 * stage was not timed since the last reset. */
float fc_stage_timer_ms(const fc_stage_timer *t, fc_stage stage);

#endif
