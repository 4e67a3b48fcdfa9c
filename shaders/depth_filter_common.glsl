#version 450 core
// What the separable depth filters (bilateral, narrow-range, binomial) share:
// one 1-D pass along `axis` over linear view depth (z > 0; 0 = background)
// and the kernel half-width, fixed or from the projected particle size.
// A library without a stage: linked into each filter's program, fragment
// (bilateral, binomial) or compute (narrow-range); the uniforms are set by
// separable_filter.c.

layout(binding = 0) uniform sampler2D depth_in;

layout(location = 0) uniform ivec2 axis;              // (1, 0) horizontal pass, (0, 1) vertical
layout(location = 1) uniform vec2 pixel_scale;        // (Cx, Cy) of the grid being filtered
layout(location = 2) uniform float particle_radius;   // world units
layout(location = 3) uniform float depth_jump;        // world units; larger steps separate two surfaces
layout(location = 4) uniform int fixed_radius;        // kernel half-width in pixels; 0 = from the depth
layout(location = 5) uniform float radii_per_kernel;  // auto half-width in projected particle radii
layout(location = 40) uniform ivec2 source_size;   // the image in use; the texture may be larger (stale texels)

// The largest filter_radius a request may set; also bounds the automatic
// kernel when a particle covers much of the screen.
const int MAX_KERNEL_RADIUS = 64;

bool on_grid(ivec2 p)
{
    return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, source_size));
}

ivec2 nearest_on_grid(ivec2 p)
{
    return clamp(p, ivec2(0), source_size - 1);
}

// The whole texel (filters that carry a second channel read it too); callers check on_grid first.
vec4 texel_at(ivec2 p)
{
    return texelFetch(depth_in, p, 0);
}

// Depth at p, 0 (background) off the grid.
float depth_at(ivec2 p)
{
    return on_grid(p) ? texel_at(p).r : 0.0;
}

// Radius in pixels of a sphere of particle_radius at depth z along this
// pass's axis: r / (z C), since one pixel spans C z world units there.
float projected_radius(float z)
{
    float c = axis.x != 0 ? pixel_scale.x : pixel_scale.y;
    return particle_radius / (z * c);
}

// Half-width of the kernel for a pixel at depth z: fixed, or proportional to
// the projected particle size so near and far surfaces are smoothed alike
// (the varying kernel Janisz §4.1.2.1 asks for; Truong & Yuksel §4).
int kernel_radius(float z)
{
    if (fixed_radius > 0)
        return min(fixed_radius, MAX_KERNEL_RADIUS);
    return clamp(int(ceil(radii_per_kernel * projected_radius(z))), 1, MAX_KERNEL_RADIUS);
}

// One side of a kernel, walked outward from its centre. A sample belongs to
// the centre's surface while no step between consecutive fluid samples
// exceeds the depth jump: background in between (a hole) is skipped, the
// first larger step ends the surface on that side. Comparing neighbours with
// each other rather than with the centre lets a kernel follow a steep but
// continuous surface (a sphere's rim, a floor seen at a grazing angle) while
// never crossing into another surface.
struct surface_walk {
    float last;   // depth of the last sample on the surface; 0 before the first
    bool ended;
};

surface_walk walk_from(float z)
{
    return surface_walk(z, false);
}

// Whether zi, the next sample outward, is on the walk's surface.
bool walk_accepts(inout surface_walk walk, float zi)
{
    if (walk.ended || zi <= 0.0)
        return false;
    if (walk.last > 0.0 && abs(zi - walk.last) > depth_jump) {
        walk.ended = true;
        return false;
    }
    walk.last = zi;
    return true;
}
