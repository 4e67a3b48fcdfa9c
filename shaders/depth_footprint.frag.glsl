#version 450 core
// The four texels of a low-resolution depth image around a full-resolution
// pixel, with their bilinear weights, grouped by surface. Shared by the
// depth upsampling and the colour blend over silhouettes.

layout(location = 0) uniform int block;           // full-resolution pixels per texel along each axis
layout(location = 1) uniform float depth_jump;    // world units; larger steps separate two surfaces
layout(location = 41) uniform ivec2 low_size;     // the low-resolution image in use, within its texture

struct footprint {
    ivec2 texel[4];
    float depth[4];    // 0 = background
    float weight[4];   // bilinear, summing to 1
};

footprint footprint_at(sampler2D low_depth, ivec2 p)
{
    vec2 u = (vec2(p) + 0.5) / float(block) - 0.5;
    ivec2 base = ivec2(floor(u));
    vec2 f = u - floor(u);
    ivec2 last = low_size - 1;
    footprint fp;
    for (int i = 0; i < 4; i++) {
        ivec2 corner = ivec2(i & 1, i >> 1);
        // Clamped at the edges, as fluid leaving the image continues beyond it.
        fp.texel[i] = clamp(base + corner, ivec2(0), last);
        fp.depth[i] = texelFetch(low_depth, fp.texel[i], 0).r;
        vec2 along = mix(1.0 - f, f, vec2(corner));
        fp.weight[i] = along.x * along.y;
    }
    return fp;
}

bool same_surface(float a, float b)
{
    return a > 0.0 && b > 0.0 && abs(a - b) <= depth_jump;
}

// The surface holding most of the bilinear weight, as the index of one of its
// texels, or -1 when the background does. Ties go to the nearer surface, as
// the nearest surface is the one a pixel shows.
int dominant_surface(footprint fp)
{
    float background = 0.0;
    for (int i = 0; i < 4; i++)
        background += fp.depth[i] > 0.0 ? 0.0 : fp.weight[i];
    int best = -1;
    float best_weight = background;
    for (int i = 0; i < 4; i++) {
        if (fp.depth[i] <= 0.0)
            continue;
        float w = 0.0;
        for (int j = 0; j < 4; j++)
            w += same_surface(fp.depth[i], fp.depth[j]) ? fp.weight[j] : 0.0;
        bool nearer = best < 0 || fp.depth[i] < fp.depth[best];
        if (w > best_weight || (w == best_weight && nearer)) {
            best = i;
            best_weight = w;
        }
    }
    return best;
}

// Whether the four texels show more than one thing: fluid and background, or
// two separate surfaces.
bool straddles_silhouette(footprint fp)
{
    for (int i = 1; i < 4; i++) {
        bool both_background = fp.depth[0] <= 0.0 && fp.depth[i] <= 0.0;
        if (!both_background && !same_surface(fp.depth[0], fp.depth[i]))
            return true;
    }
    return false;
}
