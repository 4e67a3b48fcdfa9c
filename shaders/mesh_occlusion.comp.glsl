#version 450 core
// The fluid hidden by opaque meshes: where the nearest opaque mesh surface
// is nearer than the fluid's nearest surface, the pixel shows no fluid (its
// depth becomes 0). The fluid's depth is the nearest over all its particles,
// so this is what testing every particle's fragments against the mesh would
// leave: a particle inside or behind a mesh is not drawn in front of it.

layout(local_size_x = 8, local_size_y = 8) in;

layout(r32f, binding = 0) uniform image2D fluid_depth;   // linear depth, 0 = no fluid
layout(binding = 1) uniform sampler2D mesh_depth;        // linear depth, 0 = no mesh
layout(location = 0) uniform ivec2 size;                 // the image in use

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    float mesh = texelFetch(mesh_depth, p, 0).r;
    float fluid = imageLoad(fluid_depth, p).r;
    if (mesh > 0.0 && fluid > mesh)
        imageStore(fluid_depth, p, vec4(0.0));
}
