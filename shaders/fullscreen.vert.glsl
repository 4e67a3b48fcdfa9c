#version 450 core
// One triangle that covers the viewport, drawn without vertex buffers;
// full-screen passes address their inputs by gl_FragCoord.

#ifdef FC_FLAT_CONSTANTS
// Generated (flat_constants.h): hands the fragment stage's uniforms on as flat
// outputs, which llvmpipe reads far more cheaply than uniforms.
void fc_forward_constants();
#endif

void main()
{
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);   // (0,0) (2,0) (0,2)
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
#ifdef FC_FLAT_CONSTANTS
    fc_forward_constants();
#endif
}
