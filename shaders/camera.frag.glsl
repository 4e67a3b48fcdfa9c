#version 450 core
// The camera as full-screen passes see it: window position -> view-space ray
// -> world space. Linked into the background and composite programs.

layout(location = 0) uniform vec2 focal;           // P[0][0], P[1][1]
layout(location = 1) uniform mat3 view_to_world;   // rotation of the inverse view matrix
layout(location = 4) uniform vec3 eye_world;
layout(location = 5) uniform vec2 viewport;        // pixels

// View-space direction through a window position, scaled to z = -1 so that
// multiplying it by a linear depth gives the view-space point at that depth.
vec3 view_ray(vec2 window)
{
    vec2 ndc = window / viewport * 2.0 - 1.0;
    return vec3(ndc / focal, -1.0);
}

vec3 to_world_point(vec3 view_point)
{
    return eye_world + view_to_world * view_point;
}

vec3 to_world_direction(vec3 view_direction)
{
    return view_to_world * view_direction;
}
