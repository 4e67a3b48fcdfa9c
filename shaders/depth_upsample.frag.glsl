#version 450 core
// Reduced-resolution smoothing (van der Laan et al. 2009, §3.5.1), step 3:
// the smoothed low-resolution depth back at full resolution. Inside a surface
// depth is interpolated bilinearly. Where the four texels around a pixel show
// different things, the pixel's own unsmoothed depth picks the surface it
// belongs to, so outlines between surfaces keep their full-resolution shape
// instead of the texels' staircase; a pixel without fluid, or on a surface no
// texel holds, takes what has most of the bilinear weight (this is how the
// smoothing's own changes to the outline come through). Depth is interpolated
// over the chosen surface's texels only, so surfaces never blend with each
// other or with the background. The silhouettes left are softened by blending
// the shaded colour over them (silhouette_blend.frag.glsl), as the paper
// does, rather than by blending depth.

struct footprint {
    ivec2 texel[4];
    float depth[4];
    float weight[4];
};
footprint footprint_at(sampler2D low_depth, ivec2 p);
bool same_surface(float a, float b);
int dominant_surface(footprint fp);

layout(binding = 0) uniform sampler2D low_depth;    // smoothed, 0 = background
layout(binding = 1) uniform sampler2D full_depth;   // unsmoothed, full resolution

// The texel on the same surface as depth z nearest to it in depth, or -1.
int surface_holding(footprint fp, float z)
{
    int best = -1;
    for (int i = 0; i < 4; i++)
        if (same_surface(fp.depth[i], z) && (best < 0 || abs(fp.depth[i] - z) < abs(fp.depth[best] - z)))
            best = i;
    return best;
}

layout(location = 0) out float depth_out;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    footprint fp = footprint_at(low_depth, p);
    int surface = surface_holding(fp, texelFetch(full_depth, p, 0).r);
    if (surface < 0)
        surface = dominant_surface(fp);
    if (surface < 0) {
        depth_out = 0.0;
        return;
    }
    float weighted = 0.0, total = 0.0;
    for (int i = 0; i < 4; i++)
        if (same_surface(fp.depth[surface], fp.depth[i])) {
            weighted += fp.weight[i] * fp.depth[i];
            total += fp.weight[i];
        }
    depth_out = weighted / total;
}
