#version 450 core
// One explicit Euler step of screen-space curvature flow (van der Laan et al.
// 2009, §3.2, eqs. 1-8) on linear view depth z > 0; z = 0 is background.
//
// A compute shader, so that one invocation can step a BLOCK_W x BLOCK_H block
// of pixels: it fetches the block and a one-pixel border once, (BLOCK_W + 2)
// (BLOCK_H + 2) texels, where a fragment shader fetched the nine of its 3x3
// stencil for every pixel. Fetches dominate on a software rasterizer; the
// arithmetic of each pixel is the fragment version's, so are the results.

layout(binding = 0) uniform sampler2D depth_in;
layout(binding = 0, r32f) uniform writeonly image2D depth_out;

layout(location = 0) uniform vec2 pixel_scale;  // (Cx, Cy) = (2 / (Vx Fx), 2 / (Vy Fy))
layout(location = 1) uniform float depth_jump;  // world units; larger steps separate two surfaces
layout(location = 40) uniform ivec2 source_size;   // the image in use; the texture may be larger (stale texels)

layout(local_size_x = 8, local_size_y = 8) in;
// The pixels of an invocation (main spells out all 16).
#define BLOCK_W 4
#define BLOCK_H 4
const int SPAN = BLOCK_W + 2;
// The block with its border, rows bottom to top; 0 (background) off the grid.
float window[SPAN * (BLOCK_H + 2)];

void load_window(ivec2 origin, ivec2 size)
{
    for (int y = 0; y < BLOCK_H + 2; y++)
        for (int x = 0; x < SPAN; x++) {
            ivec2 p = origin + ivec2(x - 1, y - 1);
            bool on_grid = all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, size));
            window[y * SPAN + x] = on_grid ? texelFetch(depth_in, p, 0).r : 0.0;
        }
}

// Whether the pixel at `offset` from the block pixel `b` shows the same
// surface as depth z: not background (off the grid reads as background), and
// no depth jump between them. `zn` is its depth, or z when it is not: the
// one-sided derivative towards it is then zero, so separate surfaces never
// blend and silhouettes stay put.
bool same_surface(ivec2 b, ivec2 offset, float z, out float zn)
{
    zn = z;
    ivec2 q = b + 1 + offset;
    float d = window[q.y * SPAN + q.x];
    if (d <= 0.0 || abs(d - z) > depth_jump)
        return false;
    zn = d;
    return true;
}

float neighbour(ivec2 b, ivec2 offset, float z)
{
    float zn;
    same_surface(b, offset, z, zn);
    return zn;
}

// The stepped depth of block pixel b.
float step_pixel(ivec2 b)
{
    float z = window[(b.y + 1) * SPAN + b.x + 1];
    if (z <= 0.0)
        return z;

    float z_right = neighbour(b, ivec2(1, 0), z);
    float z_left = neighbour(b, ivec2(-1, 0), z);
    float z_up = neighbour(b, ivec2(0, 1), z);
    float z_down = neighbour(b, ivec2(0, -1), z);
    float z_ur, z_ul, z_dr, z_dl;
    bool ur = same_surface(b, ivec2(1, 1), z, z_ur);
    bool ul = same_surface(b, ivec2(-1, 1), z, z_ul);
    bool dr = same_surface(b, ivec2(1, -1), z, z_dr);
    bool dl = same_surface(b, ivec2(-1, -1), z, z_dl);

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
    return z - dt * 0.5 * twice_h;
}

// Steps block pixel b and stores it, when it lies on the image.
void step_and_store(ivec2 origin, ivec2 size, ivec2 b)
{
    ivec2 p = origin + b;
    if (all(lessThan(p, size)))
        imageStore(depth_out, p, vec4(step_pixel(b)));
}

void main()
{
    ivec2 size = source_size;
    ivec2 origin = ivec2(gl_GlobalInvocationID.xy) * ivec2(BLOCK_W, BLOCK_H);
    if (any(greaterThanEqual(origin, size)))
        return;
    load_window(origin, size);
    // The BLOCK_W x BLOCK_H pixels spelled out, not looped: the compiler keeps
    // a loop of this size rolled, and indexing `window` by its counter costs a
    // loop over the SIMD lanes on llvmpipe (measured 1.3-1.7x slower).
    step_and_store(origin, size, ivec2(0, 0)); step_and_store(origin, size, ivec2(1, 0));
    step_and_store(origin, size, ivec2(2, 0)); step_and_store(origin, size, ivec2(3, 0));
    step_and_store(origin, size, ivec2(0, 1)); step_and_store(origin, size, ivec2(1, 1));
    step_and_store(origin, size, ivec2(2, 1)); step_and_store(origin, size, ivec2(3, 1));
    step_and_store(origin, size, ivec2(0, 2)); step_and_store(origin, size, ivec2(1, 2));
    step_and_store(origin, size, ivec2(2, 2)); step_and_store(origin, size, ivec2(3, 2));
    step_and_store(origin, size, ivec2(0, 3)); step_and_store(origin, size, ivec2(1, 3));
    step_and_store(origin, size, ivec2(2, 3)); step_and_store(origin, size, ivec2(3, 3));
}
