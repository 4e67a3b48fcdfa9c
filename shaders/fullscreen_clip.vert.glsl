#version 450 core
// The full-screen triangle of fullscreen.vert.glsl cut by two planes, so
// that a draw covers one region of the image (background_regions.h); the
// planes are linear in NDC, so interpolating them across the triangle is exact.

layout(location = 56) uniform vec3 clip_planes[2];   // dot(xy, ndc) + z >= 0 is drawn

out gl_PerVertex {
    vec4 gl_Position;
    float gl_ClipDistance[2];
};

#ifdef FC_FLAT_CONSTANTS
// Generated (flat_constants.h): hands the fragment stage's uniforms on as flat
// outputs, which llvmpipe reads far more cheaply than uniforms.
void fc_forward_constants();
#endif

void main()
{
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);   // (0,0) (2,0) (0,2)
    vec2 ndc = corner * 2.0 - 1.0;
    gl_Position = vec4(ndc, 0.0, 1.0);
    for (int i = 0; i < 2; i++)
        gl_ClipDistance[i] = dot(clip_planes[i].xy, ndc) + clip_planes[i].z;
#ifdef FC_FLAT_CONSTANTS
    fc_forward_constants();
#endif
}
