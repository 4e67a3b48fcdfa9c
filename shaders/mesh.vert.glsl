#version 450 core
// A client's mesh (PROTOCOL.md section 12) through a camera: its transform
// and the view in one matrix, then the view's perspective (fc_view: focal
// lengths and the depth part). Linked into the mesh programs (mesh_pass.c),
// for the image's camera and for the sun's.

layout(location = 0) in vec3 position;   // the mesh's own frame
layout(location = 1) in vec3 normal;     // the same frame; absent without normals

layout(location = 60) uniform mat4 mesh_to_view;
layout(location = 64) uniform mat3 normal_to_view;   // inverse transpose of mesh_to_view's 3x3
layout(location = 67) uniform vec4 projection;       // fx, fy, P[2][2], P[3][2]

out vec3 view_position;
out vec3 view_normal;

void main()
{
    vec4 v = mesh_to_view * vec4(position, 1.0);
    view_position = v.xyz;
    view_normal = normal_to_view * normal;
    gl_Position = vec4(projection.x * v.x, projection.y * v.y, projection.z * v.z + projection.w, -v.z);
}
