/* particle_attributes.h — what the shading passes know of each particle beyond
 * its position (id, speed, noise amplitude), in shader storage buffers read by
 * particle_attributes.frag.glsl, and the draw order that puts the surface
 * particles before the spray.
 *
 * Both buffers are persistently mapped, like the positions (particle_buffer.h):
 * a frame's attributes are written once, straight into memory the GPU reads.
 * The amplitudes have a buffer of their own because the foam state sets them
 * after the upload: replacing them rewrites 4 bytes per particle, not the
 * records. Densities stay on the CPU, which alone reads them.
 *
 * An upload keeps the frame's order: sorting by density (and gathering every
 * attribute into that order) costs about ten times the upload of a
 * 1M-particle frame, and only renders with spray need it (a density
 * threshold or neighbour classes, spray_classes.h). Such a render reorders
 * the uploaded frame once per classification (fc_particle_attributes_order_by_density). */
#ifndef FC_PARTICLE_ATTRIBUTES_H
#define FC_PARTICLE_ATTRIBUTES_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "density_order.h"
#include "fluidcast_types.h"
#include "gpu_memory.h"

/* One particle as the shaders see it (std430: two 4-byte members). */
typedef struct fc_particle_record {
    uint32_t id;        /* persistent id, or the frame index when the frame has none */
    float speed;        /* |velocity|, 0 without velocities */
} fc_particle_record;

/* Binding points in the shaders: the records, and the noise amplitude
 * multipliers (one float per particle, 1 when calm). */
#define FC_PARTICLE_RECORDS_BINDING 0
#define FC_PARTICLE_AMPLITUDES_BINDING 1

typedef struct fc_particle_attributes {
    GLuint records;                     /* fc_particle_record per particle, draw order */
    GLuint amplitudes;                  /* float per particle, draw order */
    fc_particle_record *mapped_records; /* both mapped for writing as long as they live */
    float *mapped_amplitudes;
    uint64_t gpu_capacity;              /* particles both buffers hold; they only grow */
    uint32_t gpu_allocations;           /* times a buffer was (re)allocated */
    /* Leading records known to hold (draw slot, speed 0) and leading amplitudes
     * known to be 1: what a frame of positions alone needs, kept from earlier
     * frames instead of being written again. */
    uint64_t plain_records;
    uint64_t calm_amplitudes;
    bool amplitudes_set;                /* the uploaded frame's amplitudes were given */
    uint64_t count;
    bool reorderable;                   /* the uploaded frame has particles: it may be sorted later */
    bool by_density;                    /* draw order is order.order (densest first), else the frame's */
    uint32_t ordered_classes;           /* the spray_neighbours the order's keys were classified with */
    fc_density_order order;
    /* The amplitudes set while a reorderable frame is in its own order, kept
     * in frame order so a reorder can gather them (the mapped buffer is
     * write-only); `frame_amplitudes_set` says they belong to this frame. */
    float *frame_amplitudes;
    uint64_t frame_amplitude_capacity;
    bool frame_amplitudes_set;
    uint64_t density_sorts;             /* times a frame was sorted by density, for tests and benchmarks */
} fc_particle_attributes;

fc_code fc_particle_attributes_create(fc_particle_attributes *a, fc_error *err);
void fc_particle_attributes_destroy(fc_particle_attributes *a);

/* Takes the frame's attributes in the frame's order. The caller has waited
 * for the GPU to finish the draws that read the last frame
 * (fc_particle_buffer_reserve). */
fc_code fc_particle_attributes_upload(fc_particle_attributes *a, const fc_frame *frame, fc_error *err);

/* Puts the uploaded frame (the same `frame`, unchanged since the upload) in
 * the descending order of `keys` (frame order; spray_classes.h: the density,
 * 0 for spray), amplitudes included, once the GPU is done with every draw
 * issued so far — so the caller may then rewrite the positions in the new
 * order too. `classes` (the spray_neighbours the keys were classified with)
 * is the order's cache key: does nothing when the frame is in the order of
 * those classes already or has no particles. On failure the frame is in its
 * own order. */
fc_code fc_particle_attributes_order_by_density(fc_particle_attributes *a, const fc_frame *frame, const float *keys,
                                                uint32_t classes, fc_error *err);

/* Draw slot -> frame index of the uploaded frame; NULL when the draw order is the frame's. */
const uint32_t *fc_particle_attributes_draw_order(const fc_particle_attributes *a);

/* How many particles, from the start of the draw order, make up the surface:
 * those with density >= threshold; all of them when the threshold is <= 0 or
 * the frame is not in density order (the caller orders a frame with
 * densities first when it asks with a threshold). */
uint64_t fc_particle_attributes_surface_count(const fc_particle_attributes *a, float density_threshold);

/* Replaces every particle's noise amplitude; `amplitude` is in frame order
 * and has one entry per particle of the uploaded frame. Waits for the draws
 * still reading the amplitudes before. */
fc_code fc_particle_attributes_set_amplitudes(fc_particle_attributes *a, const float *amplitude, fc_error *err);

/* Gives every particle the calm amplitude 1 unless its frame's amplitudes
 * were set since the upload: called before the first draw of a frame, so an
 * upload followed by set_amplitudes writes the amplitudes once. */
void fc_particle_attributes_settle(fc_particle_attributes *a);

/* Binds the record and amplitude buffers for the next draws. */
void fc_particle_attributes_bind(const fc_particle_attributes *a);

/* Adds the GPU buffers' bytes (gpu_capacity x 12) and allocations to m's particles. */
void fc_particle_attributes_tally(const fc_particle_attributes *a, fc_gpu_memory *m);

#endif
