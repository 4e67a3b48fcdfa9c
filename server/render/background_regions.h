/* background_regions.h — the background pass's draws, each over the part of
 * the image where a cheaper shader variant gives the same pixels.
 *
 * A software rasterizer runs every branch of a shader for every pixel, so a
 * pixel of the floor pays for the sky's shading and one far from the fluid's
 * shadow for the shadow's lookup. Drawn region by region, each with the
 * variant (shader_variants.h) that leaves out what the region cannot show,
 * the pixels are the same and the work less: the sky above the horizon line,
 * the floor below it (FC_FEATURE_FLOOR_ONLY), the general program on a band a
 * few pixels wide around the line (where the shader's own test decides), and
 * on the floor the shadow's lookup only inside a rectangle holding every
 * floor point whose sun ray meets the fluid's box. */
#ifndef FC_BACKGROUND_REGIONS_H
#define FC_BACKGROUND_REGIONS_H

#include <stdbool.h>

#include "environment.h"
#include "view.h"

#define FC_BACKGROUND_DRAWS_MAX 7

typedef struct fc_background_draw {
    unsigned features;          /* the variant's (shader_variants.h) */
    float clip_planes[2][3];    /* NDC: dot(xy, ndc) + z >= 0 is drawn (fullscreen_clip.vert.glsl) */
    bool scissored;
    int scissor[4];             /* x, y, width, height in pixels, when scissored */
} fc_background_draw;

/* The draws that together cover the view (overlapping by a pixel where
 * clipped, so that no pixel falls between two: either program gives it the
 * same colour) for a render that needs `features`; returns their count. */
int fc_background_regions(const fc_view *view, const fc_environment *env, unsigned features,
                          fc_background_draw draws[FC_BACKGROUND_DRAWS_MAX]);

#endif
