/* particle_buffer.h — the uploaded frame's positions in a GL buffer, plus the
 * bounds the camera and the floor are derived from.
 *
 * The buffer is persistently mapped: a frame is copied straight into memory
 * the GPU reads, once. On a discrete GPU glBufferSubData copies the frame
 * into a driver staging buffer first, and may stall until draws still reading
 * the buffer finish; here the only wait is a fence on the draws of the frame
 * before (already done when a render's readback ended it). */
#ifndef FC_PARTICLE_BUFFER_H
#define FC_PARTICLE_BUFFER_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "gpu_memory.h"

typedef struct fc_particle_buffer {
    GLuint vertex_array;    /* attribute 0 = vec3 position */
    GLuint buffer;
    float *mapped;          /* the buffer's storage, mapped for writing as long as it lives */
    uint64_t capacity;      /* particles the buffer holds; it only ever grows */
    uint64_t count;         /* particles of the current frame */
    uint32_t allocations;   /* times the GL buffer was (re)allocated */
    float lo[3], hi[3];     /* bounds of the current frame; a point at the origin when empty */
    uint64_t generation;    /* counts the fills: what is derived from the positions (anisotropy.h) is
                               stale once it changes */
    GLuint shapes;          /* per-slot ellipsoids the splats ray-cast (anisotropy.h), set for a render;
                               0: spheres */
} fc_particle_buffer;

fc_code fc_particle_buffer_create(fc_particle_buffer *pb, fc_error *err);
void fc_particle_buffer_destroy(fc_particle_buffer *pb);

/* Makes room for a frame of `count` particles and empties the buffer,
 * reallocating it only when the frame is larger than any before, after the
 * GPU is done with every draw issued so far (so any buffer those draws read
 * may be overwritten then). FC_ERR_RENDER when the GPU has no room for the
 * frame or does not finish those draws. */
fc_code fc_particle_buffer_reserve(fc_particle_buffer *pb, uint64_t count, fc_error *err);

/* Copies the frame's positions into the reserved buffer in draw order
 * (order[slot] = frame index; NULL: the frame's order) and bounds them in
 * the same pass. */
void fc_particle_buffer_fill(fc_particle_buffer *pb, const fc_frame *frame, const uint32_t *order);

/* Reserve, then fill in the frame's order. */
fc_code fc_particle_buffer_upload(fc_particle_buffer *pb, const fc_frame *frame, fc_error *err);

/* Binds the vertex array with a position per vertex (point sprites) or per
 * instance (quads: instance i reads particle i from the base instance on). */
void fc_particle_buffer_bind(const fc_particle_buffer *pb, bool per_instance);

/* Adds the buffer's bytes (capacity x 12) and allocations to m's particles. */
void fc_particle_buffer_tally(const fc_particle_buffer *pb, fc_gpu_memory *m);

#endif
