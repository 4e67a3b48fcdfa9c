#version 450 core
// Closing pinholes in the splatted depth: where no particle covers a pixel
// but fluid lies on both sides of it along every one of four directions
// (across, down and both diagonals) within a fraction of a particle's
// projected radius, at depths close to each other, the pixel is a gap
// between the particles of one surface (a jittered sheet's spheres leave
// them), not background: it gets the depth interpolated across it.
// Requiring all four directions keeps the gaps between separate bodies,
// which are open along their length, and every silhouette untouched.
// Linked into depth_resolve.frag.glsl and pinhole_fill.comp.glsl, which
// define splat_depth_at. The compute splat calls filled_depth only in the
// tiles fill_candidates.comp.glsl lists, which relies on this: no pixel is
// filled unless the walks along +x, -x, +y and -y all find fluid within
// the texels of fill_steps steps; a change here must keep that, or change
// the marking. Large sprites leave gaps wider than dense_steps texels: a
// walk's steps past the first dense_steps then stride over fill_stride
// texels each, so a walk reaches as far as the gaps of any sprite size with
// at most max_reach steps.

float splat_depth_at(ivec2 p);   // +inf where no particle is, and outside the image

layout(location = 50) uniform float fill_reach_depth;   // reach in pixels times the depth there
layout(location = 51) uniform float fill_max_step;      // depths across a gap differ by less
layout(location = 53) uniform int fill_steps;           // the walks' length, at most max_reach: no depth in
                                                        // front of the near plane lets a farther find count
layout(location = 55) uniform int fill_stride;          // texels per step past dense_steps, >= 1

const int max_reach = 12;
const int dense_steps = 6;   // steps of one texel first: small sprites' gaps are walked texel by texel

// The nearest fluid from p along d within reach: its depth and distance (0 if none).
vec2 fluid_along(ivec2 p, ivec2 d)
{
    for (int k = 1; k <= min(fill_steps, max_reach); k++) {
        int texels = k <= dense_steps ? k : dense_steps + (k - dense_steps) * fill_stride;
        float z = splat_depth_at(p + texels * d);
        if (!isinf(z))
            return float(texels) <= fill_reach_depth / z ? vec2(z, float(texels)) : vec2(0.0);
    }
    return vec2(0.0);
}

// The depth to give the empty pixel p, or +inf to leave it empty.
float filled_depth(ivec2 p)
{
    const ivec2 directions[4] = ivec2[4](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1), ivec2(1, -1));
    float sum = 0.0;
    for (int i = 0; i < 4; i++) {
        vec2 a = fluid_along(p, directions[i]);
        if (a.y == 0.0)
            return uintBitsToFloat(0x7f800000u);
        vec2 b = fluid_along(p, -directions[i]);
        if (b.y == 0.0 || abs(a.x - b.x) > fill_max_step)
            return uintBitsToFloat(0x7f800000u);
        sum += (a.x * b.y + b.x * a.y) / (a.y + b.y);   // linear across the gap
    }
    return 0.25 * sum;
}
