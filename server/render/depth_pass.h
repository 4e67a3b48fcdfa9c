/* depth_pass.h — sphere depth splatting (van der Laan et al. 2009, §3.1):
 * linear view depth of the nearest sphere surface per pixel, 0 = no fluid;
 * the same splat also sums the spheres' full-resolution thickness (§3.3),
 * so the spheres are rasterised once for both (surface_splat.frag.glsl), or
 * walked once by the compute splat (compute_splat.h) where sprites are small. */
#ifndef FC_DEPTH_PASS_H
#define FC_DEPTH_PASS_H

#include "compute_splat.h"
#include "render_target.h"
#include "sphere_sprites.h"

/* How the spheres are splatted: sprites through the rasterizer, or the
 * compute splat (compute_splat.h); AUTO chooses per render by the projected
 * sprite size (fc_depth_pass_choose). Tests and the benchmark force one;
 * requests cannot. */
typedef enum fc_splat_method { FC_SPLAT_AUTO, FC_SPLAT_FRAGMENT, FC_SPLAT_COMPUTE } fc_splat_method;

typedef struct fc_depth_pass {
    fc_sphere_sprites sprites;
    GLuint resolve_program;
    GLuint empty_vertex_array;
    GLuint splat_framebuffer;     /* raw depth + thickness as attachments 0 and 1 */
    fc_render_target raw;         /* R32F nearest depth, +inf where no sphere is */
    fc_render_target thickness;   /* R32F thickness, unblurred, bilinear */
    fc_render_target target;      /* R32F linear depth, 0 = no fluid */
    fc_compute_splat compute;
    fc_splat_method method;       /* AUTO unless forced */
    fc_splat_method last_used;    /* FRAGMENT or COMPUTE: what the last run chose */
} fc_depth_pass;

fc_code fc_depth_pass_create(const char *shader_dir, fc_depth_pass *pass, fc_error *err);
void fc_depth_pass_destroy(fc_depth_pass *pass);

/* The splat a render of spheres of `radius` with the particles inside
 * [lo, hi] gets when `wanted`: FRAGMENT when wanted; COMPUTE when wanted or,
 * for AUTO, when the sprites are small; but FRAGMENT whenever a sprite may
 * be too large for the compute splat (a sphere close to the camera). */
fc_splat_method fc_depth_pass_choose(const fc_view *view, const float lo[3], const float hi[3], float radius,
                                     fc_splat_method wanted);

/* Renders the particles' depth into pass->target and, when `floor_plane`
 * is not NULL, their thickness above that view-space plane (see
 * fc_environment.floor_plane) into pass->thickness, both sized to the view. */
fc_code fc_depth_pass_run(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                          float radius, const float *floor_plane, fc_error *err);

/* Whether fc_depth_pass_run_fused can splat these particles' thickness at
 * `thickness_view`'s size (the same camera at a lower resolution) with
 * their depth in `view`: where the compute splat is chosen and can
 * (fc_compute_splat_fuses: spheres a few pixels across at that size). */
bool fc_depth_pass_fuses(const fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                         const fc_view *thickness_view, float radius);

/* Whether fc_depth_pass_run_fused can splat these particles' thickness in
 * `sun_view` (another camera: the shadow map's, at its thickness's
 * resolution) as well: spheres of at most 2x2 pixels there. */
bool fc_depth_pass_fuses_sun(const fc_depth_pass *pass, const fc_particle_buffer *particles,
                             const fc_view *sun_view, float radius);

/* The sun's thickness for fc_depth_pass_run_fused: its view, and the
 * target (another pass's, sized here to the view) it is splatted into. */
typedef struct fc_depth_sun {
    const fc_view *view;
    fc_render_target *thickness;
} fc_depth_sun;

/* fc_depth_pass_run for the depth alone which also splats the thickness
 * above `floor_plane` at `thickness_view`'s size into pass->thickness in the
 * same walk of the particles, the same bits of it as
 * fc_depth_pass_run_thickness on that view; and, where `sun` is not NULL,
 * the thickness without a floor in sun->view into sun->thickness, the same
 * bits as fc_depth_pass_run_thickness there. Only where fc_depth_pass_fuses
 * (and fc_depth_pass_fuses_sun). */
fc_code fc_depth_pass_run_fused(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                                const fc_view *thickness_view, float radius, const float *floor_plane,
                                const fc_depth_sun *sun, fc_error *err);

/* fc_depth_pass_run for the thickness above `floor_plane` (not NULL) alone,
 * the same bits of it: pass->target is neither sized nor written (the sun's
 * view where no mesh compares the fluid's depth, shadow_pass.c). */
fc_code fc_depth_pass_run_thickness(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                                    float radius, const float *floor_plane, fc_error *err);

/* Adds the pass's targets and compute-splat images to m. */
void fc_depth_pass_tally(const fc_depth_pass *pass, fc_gpu_memory *m);

/* Frees the pass's images (render targets and compute-splat images); the next run allocates them again. */
void fc_depth_pass_trim(fc_depth_pass *pass);

#endif
