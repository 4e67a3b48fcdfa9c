/* particle_buffer.h — the uploaded frame's positions in a GL buffer, plus the
 * bounds the camera and the floor are derived from, and, for a frame with
 * per-particle radii, each particle's radius as its ratio to the frame's
 * median radius in a second buffer.
 *
 * Ratios rather than radii: a splat's radius is the render's radius times
 * the ratio, so one uniform scales them all (the spray's droplets are half
 * the radius), the median is the reference size the screen-space passes need
 * (PROTOCOL.md 5), and a frame whose radii are all R renders exactly as the
 * radius setting R does (its ratios are exactly 1).
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
    /* Per-particle radii of the current frame, when it has them. */
    GLuint radii;           /* float per draw slot: the particle's radius / radius_median */
    float *mapped_radii;    /* its storage, mapped for writing as long as it lives */
    uint64_t radii_capacity;
    bool has_radii;         /* the current frame carries radii: the ratios and the two below hold */
    float radius_median;    /* the frame's median radius (fc_frame_median_radius), world units */
    float radius_ratio_max; /* the largest ratio: how far the largest particle reaches, in medians */
    bool sized;             /* set for a render: each splat's radius is the render's radius x its
                               particle's ratio; false: every particle takes the render's radius */
} fc_particle_buffer;

fc_code fc_particle_buffer_create(fc_particle_buffer *pb, fc_error *err);
void fc_particle_buffer_destroy(fc_particle_buffer *pb);

/* Makes room for a frame of `count` particles and empties the buffer,
 * reallocating it only when the frame is larger than any before, after the
 * GPU is done with every draw issued so far (so any buffer those draws read
 * may be overwritten then). With `radii`, the radius buffer too (allocated
 * at the first frame with radii, then grown like the positions'). FC_ERR_RENDER
 * when the GPU has no room for the frame or does not finish those draws. */
fc_code fc_particle_buffer_reserve(fc_particle_buffer *pb, uint64_t count, bool radii, fc_error *err);

/* The frame's median radius, found once per upload (before the fill, which
 * divides by it); a frame without radii clears has_radii. FC_ERR_NOMEM when
 * the median's scratch copy cannot be made. */
fc_code fc_particle_buffer_measure_radii(fc_particle_buffer *pb, const fc_frame *frame, fc_error *err);

/* Copies the frame's positions into the reserved buffer in draw order
 * (order[slot] = frame index; NULL: the frame's order) and bounds them in
 * the same pass; with radii (after fc_particle_buffer_measure_radii), their
 * ratios to the median in the same order. */
void fc_particle_buffer_fill(fc_particle_buffer *pb, const fc_frame *frame, const uint32_t *order);

/* Reserve, then fill in the frame's order. */
fc_code fc_particle_buffer_upload(fc_particle_buffer *pb, const fc_frame *frame, fc_error *err);

/* Binds the vertex array with a position per vertex (point sprites) or per
 * instance (quads: instance i reads particle i from the base instance on). */
void fc_particle_buffer_bind(const fc_particle_buffer *pb, bool per_instance);

/* Binds the ratios for sprites (a storage buffer) when `sized`. */
void fc_particle_buffer_bind_radii(const fc_particle_buffer *pb);

/* The radius a render's largest splat reaches: `radius` x the largest ratio
 * when sized, else `radius`. */
float fc_particle_buffer_largest_radius(const fc_particle_buffer *pb, float radius);

/* Adds the buffer's bytes (capacity x 12, plus 4 per particle of the radius
 * buffer where one was allocated) and allocations to m's particles. */
void fc_particle_buffer_tally(const fc_particle_buffer *pb, fc_gpu_memory *m);

#endif
