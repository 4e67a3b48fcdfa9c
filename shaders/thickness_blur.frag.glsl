#version 450 core
// One axis of a separable, normalised Gaussian blur of the thickness (Janisz
// 2012, §4.1.3), sampling the source bilinearly at this target's pixel
// centres: the same pass upsamples thickness computed at reduced resolution.

layout(binding = 0) uniform sampler2D source;

layout(location = 0) uniform vec2 axis;                  // (1, 0) or (0, 1): the blur axis, in source texels
layout(location = 1) uniform float sigma;                // source texels; 0 = plain resampling
layout(location = 2) uniform int taps;                   // half-width of the kernel in source texels
layout(location = 3) uniform vec2 target_size;           // pixels of the image in use
layout(location = 4) uniform vec2 source_size;           // texels of the source image in use
layout(location = 5) uniform vec2 source_texture_size;   // texels of the source texture, >= source_size

layout(location = 0) out float thickness;

void main()
{
    vec2 centre = gl_FragCoord.xy / target_size * source_size;
    float sum = 0.0, total = 0.0;
    for (int i = -taps; i <= taps; i++) {
        float w = sigma > 0.0 ? exp(-0.5 * float(i * i) / (sigma * sigma)) : 1.0;
        // Clamped to the last texel centres of the image in use, as the
        // texture's edge would clamp it: past them lie stale texels.
        vec2 texel = clamp(centre + float(i) * axis, vec2(0.5), source_size - 0.5);
        sum += w * texture(source, texel / source_texture_size).r;
        total += w;
    }
    thickness = sum / total;
}
