#version 450 core
// Where a particle's sphere lands on screen. A library without a stage:
// linked into sphere.vert.glsl (the quads bounding the sprites) and into
// surface_splat.comp.glsl (the pixels an invocation walks). `radius` is the
// sphere's, or for an ellipsoid its bounding sphere's (world units).

// Where a bound may lie at most, in NDC: well outside the image, so an
// unbounded silhouette still covers it after clipping, yet finite.
const float FAR_OUTSIDE = 4.0;

// NDC interval a sphere covers along one screen axis, from the two lines
// through the eye tangent to its circle in the (lateral, depth) plane. The
// projected silhouette is an ellipse pushed away from the projected centre, so
// the simpler r/depth estimate would cut spheres off towards the image edges.
vec2 projected_interval(float lateral, float depth, float focal, float radius)
{
    float tan_centre = lateral / depth;
    float tan_half = radius / sqrt(max(lateral * lateral + depth * depth - radius * radius, 1e-30));
    // A tangent beyond 90 degrees means an unbounded extent on that side: the
    // tiny denominator sends it far outside, where the clamp holds it.
    float lo = (tan_centre - tan_half) / max(1.0 + tan_centre * tan_half, 1e-6);
    float hi = (tan_centre + tan_half) / max(1.0 - tan_centre * tan_half, 1e-6);
    return clamp(focal * vec2(lo, hi), -FAR_OUTSIDE, FAR_OUTSIDE);
}
