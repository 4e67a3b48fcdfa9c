#version 450 core
// Compositing, first of three passes (composite_pass.c): every pixel gets the
// background and the scene's depth (the fluid's, else the floor's, else the
// far plane) for the geometry drawn later (spray). Fluid pixels are shaded
// over this by composite.frag.glsl.

bool fluid_here(out float z, out float z_floor);
float window_depth(float z);

layout(binding = 2) uniform sampler2D background;   // the scene without fluid, linear RGB

layout(location = 0) out vec4 color;

void main()
{
    float z, z_floor;
    bool fluid = fluid_here(z, z_floor);
    color = vec4(texelFetch(background, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
    gl_FragDepth = window_depth(fluid ? z : z_floor);
}
