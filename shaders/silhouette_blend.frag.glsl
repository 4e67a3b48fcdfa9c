#version 450 core
// Reduced-resolution smoothing (van der Laan et al. 2009, §3.5.1), step 4:
// "we blend the final shaded color, computed at low resolution, over edges
// instead of the normal or depth value". Where the low-resolution texels
// around a pixel straddle a silhouette, the pixel gets the bilinear blend of
// the texels' shaded colours; elsewhere the full-resolution shading stays.
// Silhouettes come out soft instead of blocky.

struct footprint {
    ivec2 texel[4];
    float depth[4];
    float weight[4];
};
footprint footprint_at(sampler2D low_depth, ivec2 p);
bool straddles_silhouette(footprint fp);

layout(binding = 0) uniform sampler2D shaded;      // the composite at full resolution, linear RGB(A)
layout(binding = 1) uniform sampler2D low_depth;   // the smoothed low-resolution depth

layout(location = 0) uniform int block;
layout(location = 40) uniform ivec2 shaded_size;   // the image in use, within the texture

layout(location = 0) out vec4 color;

// The shaded colour "computed at low resolution" for a texel: the mean over
// its block of image pixels, as a render at the texel's resolution would
// produce. A single pixel per texel would carry the sparkle of a rim's
// grazing normals into the blend as blobs a block apart.
vec4 shaded_at_texel(ivec2 texel)
{
    ivec2 size = shaded_size;
    vec4 sum = vec4(0.0);
    int count = 0;
    for (int y = 0; y < block; y++)
        for (int x = 0; x < block; x++) {
            ivec2 q = texel * block + ivec2(x, y);
            if (all(lessThan(q, size))) {
                sum += texelFetch(shaded, q, 0);
                count++;
            }
        }
    return sum / float(max(count, 1));
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    footprint fp = footprint_at(low_depth, p);
    if (!straddles_silhouette(fp)) {
        color = texelFetch(shaded, p, 0);
        return;
    }
    color = vec4(0.0);
    for (int i = 0; i < 4; i++)
        color += fp.weight[i] * shaded_at_texel(fp.texel[i]);
}
