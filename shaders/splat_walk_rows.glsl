#version 450 core
// The compute splat's walk for boxes of any size (surface_splat.comp.glsl):
// row by row, over the columns the sphere's silhouette can reach.

void splat_pixel(ivec2 p, vec3 centre);

layout(location = 1) uniform vec4 projection;        // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;          // pixels

// As sphere.vert.glsl's quads: rounding loses no pixel centre on the bounds.
const float SPAN_MARGIN_PIXELS = 0.25;

// The columns of row y whose rays may meet the sphere, within [lo, hi]: the
// walk skips the corners of the bounding box. A ray d = (a, v, -1) (a, v:
// the pixel centre's NDC over the focal lengths) meets the sphere where
// (d·c)² >= |d|² k, k = |c|² - r²: for a fixed row a quadratic in a,
// qa a² + 2 qb a + qc >= 0, whose discriminant works out to
// k (r² (1 + v²) - (c.y + v c.z)²), free of the cancellation the textbook
// form suffers. It lies between its roots when it opens downwards (qa < 0),
// as it does unless the eye is inside the sphere's tangent cylinder along x.
// A row the sphere only grazes keeps the column where it would touch, and
// the quarter pixel of margin on each side absorbs rounding (a few hundredths
// of a pixel even at the widest sprites): the ray cast decides each pixel,
// the span must only hold every one it could accept.
ivec2 row_span(int y, vec3 centre, float radius, ivec2 lo, ivec2 hi)
{
    float v = ((float(y) + 0.5) / viewport.y * 2.0 - 1.0) / projection.y;
    float r2 = radius * radius;
    float qa = r2 - centre.y * centre.y - centre.z * centre.z;
    float k = dot(centre, centre) - r2;
    if (qa >= 0.0 || k <= 0.0)
        return ivec2(lo.x, hi.x);
    float qb = centre.x * (v * centre.y - centre.z);
    float across = centre.y + v * centre.z;
    float root = sqrt(k * max(r2 * (1.0 + v * v) - across * across, 0.0));
    vec2 a = vec2(-qb + root, -qb - root) / qa;   // ascending: qa < 0
    vec2 x = (a * projection.x + 1.0) * 0.5 * viewport.x - 0.5;
    return ivec2(max(lo.x, int(ceil(x.x - SPAN_MARGIN_PIXELS))), min(hi.x, int(floor(x.y + SPAN_MARGIN_PIXELS))));
}

void walk_pixels(ivec2 lo, ivec2 hi, vec3 centre, float reach)
{
    for (int y = lo.y; y <= hi.y; y++) {
        ivec2 span = row_span(y, centre, reach, lo, hi);
        for (int x = span.x; x <= span.y; x++)
            splat_pixel(ivec2(x, y), centre);
    }
}
