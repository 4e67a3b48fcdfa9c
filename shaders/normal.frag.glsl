#version 450 core
// The normal AOV: the view-space shading normal of the fluid surface, 0
// where there is no fluid.

struct surface_spans {
    ivec2 x;
    ivec2 y;
};

float depth_at(ivec2 p);
vec3 view_point(ivec2 p, float z);
surface_spans spans_at(ivec2 p, float z);
vec3 shading_normal(ivec2 p, vec3 centre, float z, surface_spans spans);

layout(location = 0) out vec4 normal;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = depth_at(p);
    normal = z > 0.0 ? vec4(shading_normal(p, view_point(p, z), z, spans_at(p, z)), 0.0) : vec4(0.0);
}
