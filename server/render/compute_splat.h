/* compute_splat.h — the surface splat of depth_pass.h without the
 * rasterizer: one compute invocation per particle walks its sphere's pixels
 * and merges them with image atomics (surface_splat.comp.glsl), then a
 * resolve writes the same images the fragment splat does. Faster on llvmpipe
 * where sprites are small (bench/RESULTS.md, third round). */
#ifndef FC_COMPUTE_SPLAT_H
#define FC_COMPUTE_SPLAT_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "gpu_memory.h"
#include "particle_buffer.h"
#include "view.h"

/* How an invocation walks its particle's pixels: row by row over the
 * silhouette's spans; (where no box holds more than 2x2 pixel centres) the
 * four candidates without a loop; or (where a typical box holds at most 3x3)
 * nine candidates without a loop and loops for what larger boxes hold more. */
typedef enum { FC_SPLAT_WALK_ROWS, FC_SPLAT_WALK_TINY, FC_SPLAT_WALK_SMALL, FC_SPLAT_WALKS } fc_splat_walk;

/* What a run writes: the depth and the thickness; the thickness alone
 * (the sun's view where no mesh compares its depth, shadow_pass.c), built
 * with FC_THICKNESS_ONLY: the depth's load and atomic per pixel, its
 * pinhole fill and its stores left out, which llvmpipe would run behind a
 * uniform switch all the same; the depth alone (FC_DEPTH_ONLY: the
 * thickness splatted apart, at a reduced scale), which culls hidden
 * particles (surface_splat.comp.glsl); or that culled depth with the
 * thickness at a reduced scale splatted in the same walk of the particles
 * (FC_FUSED_THICKNESS: spheres only, fc_compute_splat_run_fused), and with
 * it the shadow map's thickness as well (FC_FUSED_SUN). */
typedef enum {
    FC_SPLAT_DEPTH_AND_THICKNESS,
    FC_SPLAT_THICKNESS_ONLY,
    FC_SPLAT_DEPTH_ONLY,
    FC_SPLAT_DEPTH_AND_REDUCED_THICKNESS,
    FC_SPLAT_DEPTH_REDUCED_THICKNESS_AND_SUN,
    FC_SPLAT_OUTPUTS
} fc_splat_output;

typedef struct fc_compute_splat {
    /* By output and walk: spheres, and the particles' ellipsoids (anisotropy.h) where the buffer names them
     * (none for the fused outputs, FC_SPLAT_DEPTH_AND_REDUCED_THICKNESS and ..._AND_SUN). */
    GLuint splat_program[FC_SPLAT_OUTPUTS][FC_SPLAT_WALKS];
    GLuint ellipsoid_program[FC_SPLAT_OUTPUTS][FC_SPLAT_WALKS];
    GLuint depth_resolve_program;       /* depth_resolve.frag.glsl on the splat's bits, the fill left to fill_program */
    GLuint filling_resolve_program;     /* ... with the fill's walks at every empty pixel */
    GLuint thickness_resolve_program;   /* thickness_resolve.frag.glsl */
    GLuint fill_program;                /* pinhole_fill.comp.glsl: the fill on the listed tiles */
    GLuint framebuffer;                 /* the resolves' target: the caller's depth or thickness texture */
    GLuint empty_vertex_array;          /* the resolves' full-screen triangle */
    GLuint front_program;              /* splat_front.comp.glsl: the culling's front per tile, of spheres */
    GLuint ellipsoid_front_program;    /* ... and of ellipsoids */
    GLuint tiles_program;              /* splat_tiles.comp.glsl: the culling's farthest depth per tile */
    GLuint occupancy_program;          /* fill_occupancy.comp.glsl: the tiles holding a splatted depth */
    GLuint candidates_program;         /* fill_candidates.comp.glsl: lists the tiles where the pinhole fill may fill */
    GLuint positions;                  /* buffer texture (RGB32F) over the particle buffer, during a run */
    GLuint ratios;                     /* buffer texture (R32F) over the radius ratios, during a sized run */
    uint64_t particles_per_dispatch;   /* the most particles the buffer texture may show at once */
    GLuint nearest_depth;     /* R32UI: bits of the nearest depth, +inf where no sphere is */
    GLuint thickness_sum;     /* R32UI: thickness in fixed point */
    GLuint sun_sum;           /* R32UI: the sun's thickness in fixed point, of a fused run with a sun */
    uint32_t sun_width, sun_height;   /* of sun_sum, the largest splatted so far; 0 before */
    GLuint front_tiles;       /* R32UI per CULL_TILE_PX tile: bits of the nearest particle centre's depth */
    GLuint far_tiles;         /* R32UI per tile: bits of the farthest depth splatted at its pixels */
    GLuint occupied_tiles;    /* R8UI per tile: 1 where a pixel holds a splatted depth */
    GLuint fill_list;         /* buffer: 3 workgroup counts, then the tiles where the fill's walks run */
    uint32_t width, height;   /* of the images, the largest image splatted so far; 0 before the first run */
    uint32_t allocations;     /* times the images were (re)allocated */
    fc_splat_walk last_walk;  /* of the last run with particles */
    bool cull;                /* depth alone culls hidden particles (true after create; tests compare without) */
    bool fuse;                /* fc_compute_splat_fuses may say yes (true after create; tests compare without) */
    bool last_fused;          /* the last run splatted the thickness with the depth (fc_compute_splat_run_fused) */
    bool last_fused_sun;      /* ... and the sun's thickness too */
    bool fill_candidates;     /* the pinhole fill's walks only in the tiles listed as needing them (true
                                 after create; tests compare with the walks at every empty pixel) */
} fc_compute_splat;

fc_code fc_compute_splat_create(const char *shader_dir, fc_compute_splat *s, fc_error *err);
void fc_compute_splat_destroy(fc_compute_splat *s);

/* Writes the particles' linear depth (0 = no fluid) into `depth` and, when
 * `floor_plane` is not NULL, their thickness above it into `thickness`: both
 * R32F textures of the view's size, as the fragment splat and its resolve
 * leave them. `depth` 0 (with a floor plane): the thickness alone
 * (FC_SPLAT_THICKNESS_ONLY), the same bits of it. No floor plane: the depth
 * alone (FC_SPLAT_DEPTH_ONLY), the same bits of it, culled where s->cull.
 * Ellipsoids where particles->shapes names them. `sprite` sizes the
 * particles on screen, which chooses the walk (fc_splat_walk): every walk
 * draws the same pixels. */
typedef struct fc_splat_sprite {
    float largest_px;   /* bounds every particle's projected extent in pixels along either axis (its bounding
                           sphere's, depth_pass.c): below 1.5 no box holds more than two pixel centres per axis */
    float typical_px;   /* a typical particle's extent (at the particles' middle depth); 0: unknown */
} fc_splat_sprite;

fc_code fc_compute_splat_run(fc_compute_splat *s, const fc_particle_buffer *particles, const fc_view *view,
                             float radius, fc_splat_sprite sprite, const float *floor_plane, GLuint depth,
                             GLuint thickness, fc_error *err);

/* Whether fc_compute_splat_run_fused can splat these particles' thickness
 * (sized on the thickness's view by `thickness_sprite`) with their depth:
 * spheres whose thickness takes the footprint (the small walks' sizes). */
bool fc_compute_splat_fuses(const fc_compute_splat *s, const fc_particle_buffer *particles,
                            fc_splat_sprite thickness_sprite);

/* Whether fc_compute_splat_run_fused can splat these particles' thickness
 * in a sun's view (sized there by `sun_sprite`) too: spheres of at most 2x2
 * pixels there (the tiny walk's). */
bool fc_compute_splat_fuses_sun(const fc_compute_splat *s, const fc_particle_buffer *particles,
                                fc_splat_sprite sun_sprite);

/* The sun's thickness a fused run splats as well: the shadow map's view
 * (shadow_pass.h) at its thickness's resolution, and the R32F texture of
 * that size it goes to. */
typedef struct fc_sun_splat {
    const fc_view *view;
    GLuint thickness;
} fc_sun_splat;

/* fc_compute_splat_run for the depth alone (culled where s->cull) into
 * `depth`, which also splats the thickness above `floor_plane` at
 * `thickness_view`'s size (the same camera at a lower resolution) into
 * `thickness` in the same walk of the particles, and, where `sun` is not
 * NULL, the particles' thickness in the sun's view without a floor into
 * sun->thickness: the same bits of each as the runs apart. Only where
 * fc_compute_splat_fuses (and fc_compute_splat_fuses_sun). */
fc_code fc_compute_splat_run_fused(fc_compute_splat *s, const fc_particle_buffer *particles, const fc_view *view,
                                   const fc_view *thickness_view, float radius, fc_splat_sprite sprite,
                                   const float *floor_plane, GLuint depth, GLuint thickness, const fc_sun_splat *sun,
                                   fc_error *err);

/* Adds its images' bytes and allocations to m's render targets. */
void fc_compute_splat_tally(const fc_compute_splat *s, fc_gpu_memory *m);

/* Frees its images; the next run allocates them at its size. */
void fc_compute_splat_trim(fc_compute_splat *s);

#endif
