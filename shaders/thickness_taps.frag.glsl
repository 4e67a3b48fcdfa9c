#version 450 core
// The taps of one axis of the separable, normalised Gaussian blur of the
// thickness (Janisz 2012, §4.1.3): bilinear lookups whose offsets and
// weights thickness_filter.c finds once per frame, since a software
// rasterizer pays for every tap and every exp() of every pixel. Where the
// target is smaller than the source, a tap lands between source texels and
// averages them, so the downsampling to half resolution costs no pass of its
// own; at equal sizes two neighbouring Gaussian weights share one tap between
// their texels. A fragment library, linked into the blur of the
// thickness alone (thickness_blur.frag.glsl) and of the thickness with its
// colour (thickness_color_blur.frag.glsl).

layout(binding = 0) uniform sampler2D source;

const int max_taps = 64;   // MAX_TAPS in thickness_filter.c

layout(location = 0) uniform vec2 axis;                  // (1, 0) or (0, 1): the blur axis
layout(location = 1) uniform int tap_count;              // <= max_taps
layout(location = 2) uniform vec2 source_per_target;     // source texels per target pixel, per axis
layout(location = 3) uniform vec2 source_size;           // texels of the source image in use
layout(location = 4) uniform vec2 source_texel_uv;       // 1 / the source texture's size (>= source_size)
layout(location = 8) uniform vec2 taps[max_taps];        // (offset along axis in source texels, weight); weights sum to 1

int blur_tap_count()
{
    return tap_count;
}

float blur_tap_weight(int i)
{
    return taps[i].y;
}

// Where tap i of this pixel reads the source, as a texture coordinate.
vec2 blur_tap_uv(int i)
{
    vec2 centre = gl_FragCoord.xy * source_per_target;
    // Clamped to the last texel centres of the image in use, as the
    // texture's edge would clamp it: past them lie stale texels. A merged
    // tap past the edge then reads the edge texel with both weights,
    // exactly what the two clamped taps would read.
    vec2 texel = clamp(centre + taps[i].x * axis, vec2(0.5), source_size - 0.5);
    return texel * source_texel_uv;
}
