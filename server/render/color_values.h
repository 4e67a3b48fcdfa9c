/* color_values.h — the attribute the fluid is coloured by (fc_settings.color_by),
 * one float per particle in draw order, in a shader storage buffer that
 * thickness_color.frag.glsl reads. Only a render that colours allocates and
 * fills it, and only when the frame, its draw order or the attribute changed
 * since the last fill. */
#ifndef FC_COLOR_VALUES_H
#define FC_COLOR_VALUES_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "gpu_memory.h"

/* Binding point of the values in thickness_color.frag.glsl. */
#define FC_COLOR_VALUES_BINDING 6

typedef struct fc_color_values {
    GLuint buffer;          /* 0 until a render colours */
    uint64_t capacity;      /* floats the buffer holds; it only grows */
    float *staging;         /* the values on the CPU, gathered into draw order */
    uint64_t staging_capacity;
    uint32_t allocations;
    /* What the buffer holds: the upload, the draw order and the attribute it was filled for. */
    uint64_t filled_upload;  /* 0: nothing */
    const uint32_t *filled_order;
    fc_color_by filled_by;
} fc_color_values;

/* Nothing allocated. */
fc_color_values fc_color_values_init(void);
void fc_color_values_release(fc_color_values *v);

/* Fills the buffer with `by` of each of the frame's particles in draw order
 * (`order`: draw slot -> frame index, NULL for the frame's own order), unless
 * it already holds them for `upload` (a number the caller changes with every
 * upload, never 0). FC_ERR_INVALID_VALUE naming the attribute when the frame
 * has none. */
fc_code fc_color_values_update(fc_color_values *v, const fc_frame *frame, const uint32_t *order, fc_color_by by,
                               uint64_t upload, fc_error *err);

/* Binds the buffer for the next draws. */
void fc_color_values_bind(const fc_color_values *v);

/* Adds the buffer's bytes and allocations to m's particles. */
void fc_color_values_tally(const fc_color_values *v, fc_gpu_memory *m);

#endif
