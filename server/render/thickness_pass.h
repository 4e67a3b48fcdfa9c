/* thickness_pass.h — fluid thickness (van der Laan et al. 2009, §3.3): the
 * summed length of the view ray inside every sphere above the floor, in world
 * units, optionally splatted at reduced resolution. Blurred, it is kept at
 * half the image's resolution (or the splat's, where lower) and the composite
 * samples it bilinearly: thickness is a low-frequency quantity (Janisz 2012,
 * §4.1.3), and a quarter of the pixels makes the blur about four times
 * cheaper. */
#ifndef FC_THICKNESS_PASS_H
#define FC_THICKNESS_PASS_H

#include <stdbool.h>
#include <stdint.h>

#include "color_values.h"
#include "depth_pass.h"
#include "pass_profile.h"
#include "render_target.h"
#include "sphere_sprites.h"
#include "thickness_filter.h"

typedef struct fc_thickness_pass {
    fc_thickness_filter filter;   /* blurs the depth pass's thickness (R32F) */
    /* Colouring by an attribute: the thickness and its colour (RGBA32F:
     * thickness, colour x thickness; thickness_color.frag.glsl), splatted and
     * blurred alike. Its targets are allocated by the first render that colours. */
    fc_sphere_sprites color_sprites;
    fc_render_target color_splat;
    fc_thickness_filter color_filter;
} fc_thickness_pass;

/* What colours the thickness: each particle's value, and the map from values to colours. */
typedef struct fc_thickness_color {
    const fc_color_values *values;
    float range[2];                              /* values at the map's ends */
    const float (*colormap)[3];                  /* FC_COLORMAP_ENTRIES linear RGB colours */
} fc_thickness_color;

typedef struct fc_thickness_params {
    float radius;                 /* sphere radius, world units */
    float scale;                  /* resolution relative to the view, in (0, 1] */
    uint32_t blur;                /* blur radius in image pixels (three standard deviations, resampling
                                     included); 0 = none, and the splat is the result */
    const float *floor_plane;     /* view space, see fc_environment.floor_plane */
    fc_pass_profile *profile;     /* records the splat and the filter; NULL: none */
    const char *splat_name;       /* the splat's name in the profile; NULL: "thickness splat" */
    fc_depth_pass *depth;         /* splats the thickness without a colour into its thickness target: at
                                     scale 1 it has already, with the depth; at lower scales the pass has it
                                     splat the reduced view (fc_thickness_view) unless `splatted` */
    bool splatted;                /* at a lower scale: the depth pass splatted the reduced view already, with
                                     the depth (fc_depth_pass_run_fused) */
    bool at_view_size;            /* the result resampled to the view's size (the thickness AOV) */
    const fc_thickness_color *color;   /* non-NULL: the result holds the thickness in r and the colour times
                                          the thickness in gba, always splatted by the pass (full_splat unused) */
} fc_thickness_params;

/* The view the thickness is splatted in at `scale`: the same camera at the
 * scaled size (at least a pixel per axis); sprites take their size from the
 * viewport, so it renders the same image at the lower resolution. */
fc_view fc_thickness_view(const fc_view *view, float scale);

fc_code fc_thickness_pass_create(const char *shader_dir, fc_thickness_pass *pass, fc_error *err);
void fc_thickness_pass_destroy(fc_thickness_pass *pass);

/* Accumulates the particles' thickness and sets *result to a target holding
 * it, at the view's size where params->at_view_size, else at any resolution
 * (to be sampled bilinearly): each particle's chord through its sphere, or
 * through its ellipsoid where particles->shapes names them (anisotropy.h;
 * the ellipsoids are in world space, so any view, a light's too, sees the
 * same shapes). Fluid below the floor is cut off; the fluid does not hide
 * itself (every particle adds). */
fc_code fc_thickness_pass_run(fc_thickness_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                              const fc_thickness_params *params, const fc_render_target **result, fc_error *err);

/* Adds the splat target and the filter's targets to m. */
void fc_thickness_pass_tally(const fc_thickness_pass *pass, fc_gpu_memory *m);

/* Frees the splat and blur targets; the next run allocates them again. */
void fc_thickness_pass_trim(fc_thickness_pass *pass);

#endif
