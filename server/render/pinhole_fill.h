/* pinhole_fill.h — the uniforms of pinhole_fill.glsl, which the depth
 * resolves (fragment and compute splat) link to close the gaps between the
 * particles of one surface. */
#ifndef FC_PINHOLE_FILL_H
#define FC_PINHOLE_FILL_H

#include <epoxy/gl.h>

#include "view.h"

/* Sets them on `program` for particles of `radius` seen through `view`.
 * Returns the walks' reach in texels (the texels of fill_steps steps): no pixel
 * farther than that from fluid along x and y is filled, 0: none is. */
int fc_pinhole_fill_apply(GLuint program, const fc_view *view, float radius);

#endif
