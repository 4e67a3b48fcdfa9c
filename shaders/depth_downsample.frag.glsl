#version 450 core
// Reduced-resolution smoothing (van der Laan et al. 2009, §3.5.1), step 1:
// every low-resolution texel takes the nearest fluid depth of its block of
// full-resolution pixels. The nearest, not the mean: a mean would blend
// separate surfaces and the background into depths that exist nowhere, while
// the minimum keeps what the camera sees first, so thin sheets and drops
// survive and silhouettes stay where they are.

layout(binding = 0) uniform sampler2D depth_in;   // full resolution, 0 = background

layout(location = 0) uniform int block;            // full-resolution pixels per texel along each axis
layout(location = 40) uniform ivec2 source_size;   // the image in use; the texture may be larger (stale texels)

layout(location = 0) out float depth_out;

void main()
{
    ivec2 origin = ivec2(gl_FragCoord.xy) * block;
    ivec2 size = source_size;
    float nearest = 0.0;
    for (int y = 0; y < block; y++)
        for (int x = 0; x < block; x++) {
            ivec2 p = origin + ivec2(x, y);
            if (any(greaterThanEqual(p, size)))
                continue;
            float z = texelFetch(depth_in, p, 0).r;
            if (z > 0.0 && (nearest == 0.0 || z < nearest))
                nearest = z;
        }
    depth_out = nearest;
}
