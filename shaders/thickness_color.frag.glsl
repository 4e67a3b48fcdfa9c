#version 450 core
// Thickness with the colour it carries, for colouring the fluid by a particle
// attribute: each sphere (or ellipsoid) adds its chord above the floor
// (thickness_chord.glsl) to r, and that chord times its particle's colour to
// gba. Blurred alike (thickness_color_blur.frag.glsl), gba / r is the
// thickness-weighted mean colour along the ray, which follows the surface as
// the thickness does; r stays the thickness the composite reads.

bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord);
float thickness_above_floor(vec2 pixel, float depth, float chord);

const int colormap_entries = 256;   // FC_COLORMAP_ENTRIES

// The attribute of each particle in draw order (color_values.c).
layout(std430, binding = 6) readonly buffer color_values {
    float values[];
};

layout(location = 11) uniform vec2 color_range;                   // attribute values at the map's ends
layout(location = 16) uniform vec3 colormap[colormap_entries];    // linear RGB, evenly spaced over the range

layout(location = 0) flat in vec3 sphere_centre;
layout(location = 1) flat in int particle_slot;
layout(location = 0) out vec4 thickness_color;

// The map's colour at `value`, clamped to the range's end colours and
// interpolated between entries (fc_colormap_linear does the same).
vec3 mapped_color(float value)
{
    float t = clamp((value - color_range.x) / (color_range.y - color_range.x), 0.0, 1.0);
    float pos = t * float(colormap_entries - 1);
    int i = min(int(pos), colormap_entries - 2);
    return mix(colormap[i], colormap[i + 1], pos - float(i));
}

void main()
{
    float depth, chord;
    if (!cast_particle_ray(gl_FragCoord.xy, sphere_centre, depth, chord))
        discard;
    float t = thickness_above_floor(gl_FragCoord.xy, depth, chord);
    thickness_color = vec4(t, t * mapped_color(values[particle_slot]));
}
