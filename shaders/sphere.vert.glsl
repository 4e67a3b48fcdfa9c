#version 450 core
// Particles as sprites, and the fragment shaders ray-cast the sphere (or the
// anisotropic ellipsoid, anisotropy.h) inside each one (sphere_ray.glsl,
// ellipsoid_ray.glsl), so depth and silhouette are the shape's own; an
// ellipsoid's sprite is the exact box of its projection (ellipsoid_bounds.glsl).
// Every draw comes in two parts over the same particles (sphere_sprites.c),
// and each particle is drawn by exactly one:
//  - points: a point sprite covering the projected sphere. Cheapest on a
//    software rasterizer (one primitive, not two triangles), but a point is
//    dropped whole when its centre leaves the view volume, and cannot grow
//    past GL_POINT_SIZE_RANGE (255 pixels on llvmpipe);
//  - quads: an instanced four-vertex triangle strip, the exact screen-space
//    bounding box of the projected sphere, clipped like any triangle. It
//    draws the particles points would cut off: centres outside the view,
//    spheres larger than the largest point.
// A particle the other part draws is sent outside the clip volume, where it
// is culled before rasterisation.

layout(location = 0) in vec3 position;              // world space (per vertex for points, per instance for quads)

layout(location = 0) uniform mat4 view_matrix;      // world -> view (camera looks down -z)
layout(location = 1) uniform vec4 projection;       // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;         // pixels
layout(location = 4) uniform float max_point_size;  // GL_POINT_SIZE_RANGE upper bound
layout(location = 5) uniform bool as_quads;         // which part of the draw this is
layout(location = 9) uniform int first_particle;    // quads: draw slot of the first instance

layout(location = 0) flat out vec3 sphere_centre;   // view space
layout(location = 1) flat out int particle_slot;    // draw slot, for particle_attributes.frag.glsl

// A quarter pixel of margin on each side keeps rounding from losing a pixel
// centre that lies on the silhouette's bounding box.
const float MARGIN_PIXELS = 0.25;
// A clip-space position every primitive is culled at.
const vec4 CULLED = vec4(2.0, 2.0, 2.0, 1.0);

vec2 projected_interval(float lateral, float depth, float focal, float radius);   // sphere_bounds.glsl
// The particle's bounding sphere: world centre, radius (sphere_shape.vert.glsl,
// ellipsoid_shape.vert.glsl, which also passes the ellipsoid on to the fragments).
vec4 particle_bounds(int slot, vec3 position);
// The shape's exact NDC box (x_lo, x_hi, y_lo, y_hi) where it has one of its
// own (ellipsoids), else false: the bounding sphere's intervals then.
bool particle_ndc_bounds(vec3 view_centre, vec2 focal, out vec4 box);

void main()
{
    particle_slot = as_quads ? first_particle + gl_InstanceID : gl_VertexID;
    vec4 bounds = particle_bounds(particle_slot, position);
    float reach = bounds.w;
    vec4 centre = view_matrix * vec4(bounds.xyz, 1.0);
    sphere_centre = centre.xyz;
    float depth = -centre.z;

    vec4 box;
    bool exact = particle_ndc_bounds(centre.xyz, projection.xy, box);
    vec2 x_range = exact ? box.xy : projected_interval(centre.x, depth, projection.x, reach);
    vec2 y_range = exact ? box.zw : projected_interval(centre.y, depth, projection.y, reach);
    vec2 ndc_centre = projection.xy * centre.xy / depth;
    vec2 half_extent = 0.5 * viewport * vec2(max(x_range.y - ndc_centre.x, ndc_centre.x - x_range.x),
                                             max(y_range.y - ndc_centre.y, ndc_centre.y - y_range.x));
    // One pixel of margin on each side so every pixel centre the silhouette
    // covers is rasterised.
    float point_size = 2.0 * max(half_extent.x, half_extent.y) + 2.0;
    bool point_is_exact = point_size <= max_point_size && all(lessThan(abs(ndc_centre), vec2(1.0)));
    gl_PointSize = min(point_size, max_point_size);

    // Strip order: (lo, lo), (hi, lo), (lo, hi), (hi, hi).
    vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
    vec2 margin = 2.0 * MARGIN_PIXELS / viewport;
    vec2 quad_corner = mix(vec2(x_range.x, y_range.x) - margin, vec2(x_range.y, y_range.y) + margin, corner);

    // The sprite sits at the depth of the sphere's nearest point: fragments
    // only move away from it. A sprite reaching in front of the near plane is
    // held at it instead of being clipped; the fragments in front of it are
    // discarded there.
    float front = depth - reach;
    float ndc_front = front > 0.0 ? (projection.w - projection.z * front) / front : -1.0;
    vec2 ndc = as_quads ? quad_corner : ndc_centre;
    gl_Position = vec4(ndc * depth, max(ndc_front, -1.0) * depth, depth);
    if (point_is_exact == as_quads)
        gl_Position = CULLED;
}
