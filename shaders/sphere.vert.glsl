#version 450 core
// Particles as point sprites: each sprite covers the exact perspective
// projection of its sphere, and the fragment shaders ray-cast the sphere inside
// it (sphere_ray.frag.glsl), so depth and silhouette are the sphere's own.

layout(location = 0) in vec3 position;              // world space

layout(location = 0) uniform mat4 view_matrix;      // world -> view (camera looks down -z)
layout(location = 1) uniform vec4 projection;       // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;         // pixels
layout(location = 3) uniform float radius;          // world units
layout(location = 4) uniform float max_point_size;  // GL_POINT_SIZE_RANGE upper bound

layout(location = 0) flat out vec3 sphere_centre;   // view space

// NDC interval a sphere covers along one screen axis, from the two lines
// through the eye tangent to its circle in the (lateral, depth) plane. The
// projected silhouette is an ellipse pushed away from the projected centre, so
// the simpler r/depth estimate would cut spheres off towards the image edges.
vec2 projected_interval(float lateral, float depth, float focal)
{
    float tan_centre = lateral / depth;
    float tan_half = radius / sqrt(max(lateral * lateral + depth * depth - radius * radius, 1e-30));
    // A tangent beyond 90 degrees means an unbounded extent: the clamp to
    // max_point_size then takes over.
    float lo = (tan_centre - tan_half) / max(1.0 + tan_centre * tan_half, 1e-6);
    float hi = (tan_centre + tan_half) / max(1.0 - tan_centre * tan_half, 1e-6);
    return focal * vec2(lo, hi);
}

void main()
{
    vec4 centre = view_matrix * vec4(position, 1.0);
    sphere_centre = centre.xyz;
    float depth = -centre.z;

    vec2 ndc_centre = projection.xy * centre.xy / depth;
    vec2 x_range = projected_interval(centre.x, depth, projection.x);
    vec2 y_range = projected_interval(centre.y, depth, projection.y);
    vec2 half_extent = 0.5 * viewport * vec2(max(x_range.y - ndc_centre.x, ndc_centre.x - x_range.x),
                                             max(y_range.y - ndc_centre.y, ndc_centre.y - y_range.x));
    // One pixel of margin on each side so every pixel centre the silhouette
    // covers is rasterised.
    gl_PointSize = min(2.0 * max(half_extent.x, half_extent.y) + 2.0, max_point_size);

    // The sprite sits at the depth of the sphere's nearest point: fragments only
    // move away from it (depth_greater), so early depth rejection stays valid.
    // A sprite reaching in front of the near plane is held at it instead of
    // being clipped; the fragments in front of it are discarded there.
    float front = depth - radius;
    float ndc_front = front > 0.0 ? (projection.w - projection.z * front) / front : -1.0;
    gl_Position = vec4(projection.xy * centre.xy, max(ndc_front, -1.0) * depth, depth);
}
