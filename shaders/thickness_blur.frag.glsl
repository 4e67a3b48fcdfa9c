#version 450 core
// One axis of the blur of the thickness (thickness_taps.frag.glsl): one channel.

layout(binding = 0) uniform sampler2D source;

int blur_tap_count();
float blur_tap_weight(int i);
vec2 blur_tap_uv(int i);

layout(location = 0) out float thickness;

void main()
{
    float sum = 0.0;
    for (int i = 0; i < blur_tap_count(); i++)
        sum += blur_tap_weight(i) * texture(source, blur_tap_uv(i)).r;
    thickness = sum;
}
