#version 450 core
// The thickness of a closed surface mesh along each view ray (surface_raster.c):
// drawn with additive blending and no depth test, every back face adds its
// linear depth and every front face (counter-clockwise towards the camera)
// subtracts its own, which sums to the length of the ray inside the mesh, in
// world units, as the splats' thickness is.

in vec3 view_position;
in vec3 view_normal;

layout(location = 0) out float thickness;

void main()
{
    float depth = -view_position.z;
    thickness = gl_FrontFacing ? -depth : depth;
}
