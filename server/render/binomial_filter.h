/* binomial_filter.h — Instant Liquids smoothing (Cords & Staadt, §2.2, §3):
 * iterated separable binomial kernels of one size k for the whole image,
 * then the silhouette map, which closes the fluid's outline over the kernel
 * (see binomial_filter.frag.glsl). */
#ifndef FC_BINOMIAL_FILTER_H
#define FC_BINOMIAL_FILTER_H

#include "separable_filter.h"

typedef struct fc_binomial_filter {
    fc_separable_filter passes;   /* RGBA32F, see binomial_filter.frag.glsl */
} fc_binomial_filter;

fc_code fc_binomial_filter_create(const char *shader_dir, fc_binomial_filter *b, fc_error *err);
void fc_binomial_filter_destroy(fc_binomial_filter *b);

/* The kernel half-width k in pixels of `grid`: its filter_radius, or the
 * projected particle radius at its reference depth (the paper's estimate). */
uint32_t fc_binomial_kernel_radius(const fc_smoothing_params *grid);

/* grid->iterations smoothing passes (x and y each) followed by as many
 * silhouette-map passes; *result holds the depth in its red channel
 * (`depth` itself for no iterations). */
fc_code fc_binomial_filter_run(fc_binomial_filter *b, const fc_render_target *depth, const fc_smoothing_params *grid,
                               const fc_render_target **result, fc_error *err);

#endif
