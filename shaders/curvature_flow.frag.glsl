#version 450 core
// One explicit Euler step of screen-space curvature flow (van der Laan et al.
// 2009, §3.2, eqs. 1-8) on linear view depth z > 0; z = 0 is background.

layout(binding = 0) uniform sampler2D depth_in;

layout(location = 0) uniform vec2 pixel_scale;  // (Cx, Cy) = (2 / (Vx Fx), 2 / (Vy Fy))
layout(location = 1) uniform float depth_jump;  // world units; larger steps separate two surfaces

layout(location = 0) out float depth_out;

// Whether the pixel at p shows the same surface as depth z: on screen, not
// background, and no depth jump between them. `zn` is its depth, or z when it
// is not: the one-sided derivative towards it is then zero, so separate
// surfaces never blend and silhouettes stay put.
bool same_surface(ivec2 p, float z, out float zn)
{
    zn = z;
    ivec2 size = textureSize(depth_in, 0);
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size)))
        return false;
    float d = texelFetch(depth_in, p, 0).r;
    if (d <= 0.0 || abs(d - z) > depth_jump)
        return false;
    zn = d;
    return true;
}

float neighbour(ivec2 p, float z)
{
    float zn;
    same_surface(p, z, zn);
    return zn;
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = texelFetch(depth_in, p, 0).r;
    if (z <= 0.0) {
        depth_out = z;
        return;
    }

    float z_right = neighbour(p + ivec2(1, 0), z);
    float z_left = neighbour(p + ivec2(-1, 0), z);
    float z_up = neighbour(p + ivec2(0, 1), z);
    float z_down = neighbour(p + ivec2(0, -1), z);
    float z_ur, z_ul, z_dr, z_dl;
    bool ur = same_surface(p + ivec2(1, 1), z, z_ur);
    bool ul = same_surface(p + ivec2(-1, 1), z, z_ul);
    bool dr = same_surface(p + ivec2(1, -1), z, z_dr);
    bool dl = same_surface(p + ivec2(-1, -1), z, z_dl);

    float zx = 0.5 * (z_right - z_left);
    float zy = 0.5 * (z_up - z_down);
    float zxx = z_right - 2.0 * z + z_left;
    float zyy = z_up - 2.0 * z + z_down;
    // The mixed derivative only enters through dD/dx, dD/dy; near a boundary
    // it has no meaningful stencil, and dropping it there is harmless.
    float zxy = ur && ul && dr && dl ? 0.25 * (z_ur - z_ul - z_dr + z_dl) : 0.0;

    // Eqs. 5-8 with D = Cx² Cy² D̂: every term of D̂ is of the order of z², so
    // nothing underflows single precision for large images or small depths.
    vec2 c = pixel_scale;
    float gx = zx / c.x;
    float gy = zy / c.y;
    float d_hat = gx * gx + gy * gy + z * z;
    float d_hat_x = 2.0 * (gx * zxx / c.x + gy * zxy / c.y + z * zx);
    float d_hat_y = 2.0 * (gx * zxy / c.x + gy * zyy / c.y + z * zy);
    float e_x = 0.5 * zx * d_hat_x - zxx * d_hat;
    float e_y = 0.5 * zy * d_hat_y - zyy * d_hat;
    float twice_h = (e_x / c.x + e_y / c.y) / (d_hat * sqrt(d_hat));

    // For small slopes the step is diffusion with coefficients 1/(2 Cx z) and
    // 1/(2 Cy z) per pixel², the largest it gets at any slope; explicit Euler
    // is stable for dt <= z / (1/Cx + 1/Cy). Half of that leaves margin, and
    // makes each iteration move a flat-ish surface by about Laplacian / 8.
    float dt = 0.5 * z / (1.0 / c.x + 1.0 / c.y);
    // Depth here grows away from the camera, the opposite orientation of the
    // paper's view-space z, so eq. 1 becomes dz/dt = -H (a bump flattens).
    depth_out = z - dt * 0.5 * twice_h;
}
