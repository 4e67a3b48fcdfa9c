#version 450 core
// The penumbra of the fluid's shadow (shadow_pass.c): each texel of the map
// becomes the mean of the four texels diagonally one away, a box of 4x4
// texels through bilinear filtering, as a sun of finite size softens an
// edge. Done once per texel here instead of four bilinear taps per floor
// pixel: bilinear interpolation commutes with shifts by whole texels, so one
// tap of this map (environment.frag.glsl) gives what the four gave.

layout(binding = 0) uniform sampler2D thickness;   // the blurred map, world units

layout(location = 0) uniform vec2 texel;   // 1 / the texture's size (both maps have the same)
layout(location = 1) uniform vec2 last;    // the last texel centres of the map in use, uv

layout(location = 0) out float box;

void main()
{
    vec2 uv = gl_FragCoord.xy * texel;
    float t = 0.0;
    for (int i = 0; i < 4; i++) {
        vec2 corner = vec2(i & 1, i >> 1) * 2.0 - 1.0;
        t += texture(thickness, min(uv + texel * corner, last)).r;
    }
    box = t / 4.0;
}
