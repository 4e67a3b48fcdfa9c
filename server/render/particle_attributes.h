/* particle_attributes.h — what the shading passes know of each particle beyond
 * its position (id, speed, density, noise amplitude), in a shader storage
 * buffer read by particle_attributes.frag.glsl, and the draw order that puts
 * the surface particles before the spray. */
#ifndef FC_PARTICLE_ATTRIBUTES_H
#define FC_PARTICLE_ATTRIBUTES_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "density_order.h"
#include "fluidcast_types.h"
#include "gpu_memory.h"

/* One particle as the shaders see it (std430: four 4-byte members). */
typedef struct fc_particle_record {
    uint32_t id;        /* persistent id, or the frame index when the frame has none */
    float speed;        /* |velocity|, 0 without velocities */
    float amplitude;    /* noise amplitude multiplier (foam state), 1 when calm */
    float density;      /* 0 without densities */
} fc_particle_record;

/* Binding point of the record buffer in the shaders. */
#define FC_PARTICLE_RECORDS_BINDING 0

typedef struct fc_particle_attributes {
    GLuint buffer;                 /* the records in draw order, on the GPU */
    uint64_t gpu_capacity;         /* records `buffer` holds; it only grows */
    uint32_t gpu_allocations;      /* times `buffer` was (re)allocated */
    fc_particle_record *records;   /* CPU copy in draw order */
    uint64_t record_capacity;
    float *positions;              /* positions in draw order, when that differs from the frame's */
    uint64_t position_capacity;    /* particles `positions` holds */
    uint64_t count;
    bool by_density;               /* draw order is order.order (densest first), else the frame's */
    fc_density_order order;
} fc_particle_attributes;

fc_code fc_particle_attributes_create(fc_particle_attributes *a, fc_error *err);
void fc_particle_attributes_destroy(fc_particle_attributes *a);

/* Takes the frame's attributes in draw order: densest first when the frame has
 * densities, else the frame's order. *positions receives the positions in
 * that order (the frame's own array when it is unchanged) for the position
 * buffer, then the records go to the GPU. */
fc_code fc_particle_attributes_upload(fc_particle_attributes *a, const fc_frame *frame, const float **positions,
                                      fc_error *err);

/* How many particles, from the start of the draw order, make up the surface:
 * those with density >= threshold; all of them when the threshold is <= 0 or
 * the frame has no densities. */
uint64_t fc_particle_attributes_surface_count(const fc_particle_attributes *a, float density_threshold);

/* Replaces every particle's noise amplitude; `amplitude` is in frame order
 * and has one entry per particle of the uploaded frame. */
fc_code fc_particle_attributes_set_amplitudes(fc_particle_attributes *a, const float *amplitude, fc_error *err);

/* Binds the record buffer for the next draws. */
void fc_particle_attributes_bind(const fc_particle_attributes *a);

/* Adds the GPU records' bytes (gpu_capacity x 16) and allocations to m's particles. */
void fc_particle_attributes_tally(const fc_particle_attributes *a, fc_gpu_memory *m);

#endif
