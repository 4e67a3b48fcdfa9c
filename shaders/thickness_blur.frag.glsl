#version 450 core
// One axis of a separable, normalised Gaussian blur of the thickness (Janisz
// 2012, §4.1.3), sampling the source bilinearly at this target's pixel
// centres: the same pass upsamples thickness computed at reduced resolution.

layout(binding = 0) uniform sampler2D source;

layout(location = 0) uniform vec2 texel_step;   // one source texel along the blur axis, in uv
layout(location = 1) uniform float sigma;       // source texels; 0 = plain resampling
layout(location = 2) uniform int taps;          // half-width of the kernel in source texels
layout(location = 3) uniform vec2 target_size;  // pixels

layout(location = 0) out float thickness;

void main()
{
    vec2 uv = gl_FragCoord.xy / target_size;
    float sum = 0.0, total = 0.0;
    for (int i = -taps; i <= taps; i++) {
        float w = sigma > 0.0 ? exp(-0.5 * float(i * i) / (sigma * sigma)) : 1.0;
        sum += w * texture(source, uv + float(i) * texel_step).r;
        total += w;
    }
    thickness = sum / total;
}
