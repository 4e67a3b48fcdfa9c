#version 450 core
// Compositing, the pass after the background's (composite_pass.c): survives
// only on fluid pixels, whose stencil it sets and whose depth it writes, so
// that the shading pass runs on them alone. A software rasterizer runs both
// sides of every branch for every pixel: an early-out in the shading itself
// would save nothing, the stencil test does. Where the driver lets a shader
// export the stencil, the background pass does this instead (background.frag.glsl).

bool fluid_here(out float z, out float z_floor);
float window_depth(float z);

void main()
{
    float z, z_floor;
    if (!fluid_here(z, z_floor))
        discard;
    gl_FragDepth = window_depth(z);
}
