#version 450 core
// The splatted depth in the pipeline's convention: +inf, where no sphere
// was splatted, becomes 0 = no fluid, except in the pinholes of a surface,
// which pinhole_fill.glsl closes. The fragment splat's (surface_splat.frag.glsl:
// a float texture), and with FC_SPLAT_BITS the compute splat's
// (surface_splat.comp.glsl: the float's bits in an R32UI image). A full-screen
// draw, not a compute dispatch: llvmpipe runs a compute shader's image stores
// lane by lane and pays a coroutine per 8 invocations, and the dispatch over
// the whole image cost about 100 instructions a pixel where this draw costs
// about 50 (bench/RESULTS.md). With FC_FILL_LISTED the fill is left to
// pinhole_fill.comp.glsl on the tiles where it can fill: its walks would
// otherwise run, masked, for every pixel (llvmpipe runs both sides of a
// branch).

#ifdef FC_SPLAT_BITS
layout(binding = 0) uniform usampler2D splat_depth;
#else
layout(binding = 0) uniform sampler2D splat_depth;
#endif
layout(location = 52) uniform ivec2 source_size;   // the image in use: the texture may be larger

float filled_depth(ivec2 p);

float splat_depth_at(ivec2 p)
{
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, source_size)))
        return uintBitsToFloat(0x7f800000u);
#ifdef FC_SPLAT_BITS
    return uintBitsToFloat(texelFetch(splat_depth, p, 0).r);
#else
    return texelFetch(splat_depth, p, 0).r;
#endif
}

layout(location = 0) out float depth;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = splat_depth_at(p);
#ifndef FC_FILL_LISTED
    if (isinf(z))
        z = filled_depth(p);
#endif
    depth = isinf(z) ? 0.0 : z;
}
