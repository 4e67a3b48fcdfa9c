#version 450 core
// The linear depth of the nearest mesh surface (the depth test keeps the
// nearest): what the fluid's depth is compared with (mesh_occlusion.comp.glsl),
// and, seen from the sun, what shadows the floor and the meshes.

in vec3 view_position;
in vec3 view_normal;

layout(location = 0) out float depth;

void main()
{
    depth = -view_position.z;
}
