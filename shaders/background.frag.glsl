#version 450 core
// The scene without fluid, rendered first so the composite pass can sample it
// at refracted positions (van der Laan et al. 2009, §3.5, S in eq. 14).

vec3 view_ray(vec2 window);
vec3 to_world_point(vec3 view_point);
vec3 to_world_direction(vec3 view_direction);
vec3 scene_radiance(vec3 origin, vec3 dir);

layout(location = 0) out vec4 radiance;

void main()
{
    vec3 dir = normalize(to_world_direction(view_ray(gl_FragCoord.xy)));
    radiance = vec4(scene_radiance(to_world_point(vec3(0.0)), dir), 1.0);
}
