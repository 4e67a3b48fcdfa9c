#version 450 core
// One axis of the blur of the thickness with its colour (thickness_taps.frag.glsl,
// thickness_color.frag.glsl): the four channels with the same weights, so
// colour / thickness stays the thickness-weighted mean colour.

layout(binding = 0) uniform sampler2D source;

int blur_tap_count();
float blur_tap_weight(int i);
vec2 blur_tap_uv(int i);

layout(location = 0) out vec4 thickness_color;

void main()
{
    vec4 sum = vec4(0.0);
    for (int i = 0; i < blur_tap_count(); i++)
        sum += blur_tap_weight(i) * texture(source, blur_tap_uv(i));
    thickness_color = sum;
}
