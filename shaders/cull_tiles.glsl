#version 450 core
// The tiles of the compute splat's culling (surface_splat.comp.glsl,
// FC_DEPTH_ONLY): squares of TILE_PX pixels. A library without a stage,
// linked into the splat, the front pass (splat_front.comp.glsl) and the
// farthest-depth pass (splat_tiles.comp.glsl).

layout(location = 1) uniform vec4 projection;   // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;     // pixels

// compute_splat.c's CULL_TILE_PX, as a shift: llvmpipe divides integer
// vectors lane by lane.
const int TILE_SHIFT = 2;
const int TILE_PX = 1 << TILE_SHIFT;

// The tile of a pixel (non-negative coordinates).
ivec2 tile_of(ivec2 pixel)
{
    return pixel >> TILE_SHIFT;
}

// The tile a particle's projected centre falls in (view space, depth > 0), clamped to the image.
ivec2 centre_tile(vec3 centre, float depth)
{
    vec2 ndc = projection.xy * centre.xy / depth;
    ivec2 pixel = ivec2(floor((ndc + 1.0) * 0.5 * viewport));
    return tile_of(clamp(pixel, ivec2(0), ivec2(viewport) - 1));
}
