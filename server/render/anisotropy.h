/* anisotropy.h — anisotropic particle kernels (Yu & Turk 2013, "Reconstructing
 * surfaces of particle-based fluids using anisotropic kernels"), on the GPU:
 * a uniform-grid neighbour search, then per particle the weighted covariance
 * of its neighbours, its principal axes (Jacobi) and from them an ellipsoid of
 * the sphere's volume, flat on sheets, long along jets, a sphere where it has
 * few neighbours; and its centre smoothed towards its neighbours' mean. The
 * splats ray-cast these ellipsoids where a particle buffer names them
 * (fc_particle_buffer.shapes).
 *
 * Parameters (Yu & Turk's symbols):
 *   r_s = FC_ANISOTROPY_SUPPORT_SPACINGS x the particle spacing: the support
 *         radius, Yu & Turk's 2h. The spacing is the frame's own (the median
 *         nearest-neighbour distance, fc_frame_estimate_radius / 0.9), not
 *         the render radius: radii differ by convention (the splash data
 *         suggests 0.55 spacings, the daemon's estimate is 0.9), and the
 *         neighbourhood must not. 2.2 spacings hold about 44 neighbours inside
 *         the fluid, 20-30 at its surface and on a two-layer sheet;
 *   w(d) = 1 - (d / r_s)^3 for d < r_s;
 *   lambda = FC_ANISOTROPY_LAMBDA (0.9, the paper's) for the smoothed centres;
 *   N_eps = FC_ANISOTROPY_MIN_NEIGHBOURS (the paper's 25 counts neighbours of
 *         a larger support): fewer neighbours keep the sphere, and their
 *         centre's smoothing fades out (lambda x count / N_eps), so droplets
 *         and small clusters stay round and a jet's or thin sheet's spheres
 *         stay touching, while a ball's edge particles still follow their
 *         flattened neighbours (unsmoothed, they stood out as beads: the
 *         surface mesh of a ball fell into 4 pieces); 6 made the sparse crown of the splash data
 *         spiky (needles from few-sample covariances), 12 keeps it beads;
 *   k_r = FC_ANISOTROPY_MAX_RATIO (4, the paper's): no axis is shorter than the
 *         longest / k_r, each axis proportional to its covariance eigenvalue;
 *   the three stretches multiply to 1 (the sphere's volume), so the longest
 *   is at most k_r^(2/3) = FC_ANISOTROPY_MAX_STRETCH radii, the shortest at
 *   least k_r^(-2/3). */
#ifndef FC_ANISOTROPY_H
#define FC_ANISOTROPY_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "fc_frame.h"
#include "fluidcast_types.h"
#include "gpu_memory.h"
#include "particle_buffer.h"

#define FC_ANISOTROPY_SUPPORT_SPACINGS 2.2f
#define FC_ANISOTROPY_LAMBDA 0.9f
#define FC_ANISOTROPY_MIN_NEIGHBOURS 12u
#define FC_ANISOTROPY_MAX_RATIO 4.0f
#define FC_ANISOTROPY_MAX_STRETCH 2.5198421f   /* k_r^(2/3) */

/* One particle's ellipsoid as the splats read it (std430, 48 bytes): the
 * points x with |G (x - centre)| <= radius, G symmetric (the inverse of the
 * stretch R diag(s) R^T). stretch_max == 1 exactly marks a sphere: the
 * splats then cast the sphere's own ray, bit for bit. */
typedef struct fc_ellipsoid {
    float centre[3];       /* smoothed centre, world space */
    float stretch_max;     /* the longest axis in radii: the bounding sphere's radius is radius x this */
    float inverse[6];      /* G: xx, xy, xz, yy, yz, zz */
    float neighbours;      /* neighbours within r_s, itself included */
    float unused;
} fc_ellipsoid;

typedef struct fc_anisotropy {
    GLuint count_program, scan_program, scatter_program, shape_program;
    GLuint cell_ranks;      /* uvec2 per particle: its cell, its rank in the cell */
    GLuint cell_starts;     /* counts, then (scanned in place) the first sorted slot per cell; + scan levels */
    GLuint sorted;          /* vec4 per particle in cell order: position, frame slot as bits */
    GLuint ellipsoids;      /* fc_ellipsoid per draw slot */
    uint64_t particle_capacity, cell_capacity;   /* of the buffers, which only grow */
    uint32_t allocations;
    uint32_t computations;  /* times the ellipsoids were computed (tests see the cache work) */
    /* What the ellipsoids were computed for: the cache key. */
    uint64_t generation;
    uint64_t count;
    float support;          /* r_s of the last computation, world units */
    uint32_t cells;         /* grid cells of the last computation */
    GLint max_groups;       /* GL_MAX_COMPUTE_WORK_GROUP_COUNT along x */
} fc_anisotropy;

fc_code fc_anisotropy_create(const char *shader_dir, fc_anisotropy *a, fc_error *err);
void fc_anisotropy_destroy(fc_anisotropy *a);

/* Frees the buffers; the next update allocates and computes them again. */
void fc_anisotropy_trim(fc_anisotropy *a);

/* r_s of a frame whose fc_frame_estimate_radius is `estimated_radius`
 * (0.9 spacings): FC_ANISOTROPY_SUPPORT_SPACINGS of its spacing. */
float fc_anisotropy_support(float estimated_radius);

/* Computes the ellipsoids of the particles (every slot of the buffer) over
 * neighbourhoods of radius `support` (r_s, fc_anisotropy_support), unless
 * they are already those of this upload (particles->generation): a new
 * camera, radius or render re-uses them. The ellipsoids are shapes relative
 * to the render radius, whatever it is. */
fc_code fc_anisotropy_update(fc_anisotropy *a, const fc_particle_buffer *particles, float support, fc_error *err);

/* Reads the ellipsoids of slots [0, count) back into out (tests). */
fc_code fc_anisotropy_read(const fc_anisotropy *a, uint64_t count, fc_ellipsoid *out, fc_error *err);

/* The farthest a particle's shape reaches from its centre: radius (of the
 * largest particle where they are sized, particle_buffer.h), or the longest
 * ellipsoid's where the buffer's particles are ellipsoids. */
float fc_anisotropy_reach(const fc_particle_buffer *particles, float radius);

/* Adds the buffers' bytes and allocations to m's particle bytes. */
void fc_anisotropy_tally(const fc_anisotropy *a, fc_gpu_memory *m);

#endif
