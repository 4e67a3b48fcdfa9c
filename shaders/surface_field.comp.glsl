#version 450 core
// Surface mesh, pass 1: the field at every sample of every block, its
// gradient, the particles' attributes summed with the field's weights (the
// vertices divide by the field: weighted means) and the nearest particle's id.
// Each sample sums the particles of the 3 x 3 x 3 bins around it (the
// particles come sorted by bin, surface_grid.h) in bin order, so equal input
// gives equal bits, and a sample shared by two blocks gets the same value in
// both: its bins and their order follow from its lattice point alone.
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c).

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 1) uniform vec3 origin;
layout(location = 2) uniform float cell;
layout(location = 4) uniform int kernel;   // fc_surface_kernel: 0 metaball, 1 sph (2 is 0 on ellipsoids)
layout(location = 6) uniform float bin;    // bin edge, at least the field's reach; bin 0 starts at origin
layout(location = 7) uniform uvec3 bins;   // bins along each axis

layout(std430, binding = 0) readonly buffer Particles { vec4 particles[]; };      // xyz, radius; by bin
layout(std430, binding = 1) readonly buffer Attributes { vec4 attributes[]; };    // velocity, density
layout(std430, binding = 2) readonly buffer Ids { uint ids[]; };
layout(std430, binding = 4) readonly buffer BinStarts { uint bin_starts[]; };  // x + bins.x (y + bins.y z)
layout(std430, binding = 6) writeonly buffer Field { vec4 field[]; };             // gradient, value
layout(std430, binding = 7) writeonly buffer SampleAttributes { vec4 sample_attributes[]; };
layout(std430, binding = 8) writeonly buffer SampleExtras { uvec2 sample_extras[]; }; // speed bits, id
layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };
layout(std430, binding = 9) readonly buffer Shapes { vec4 shapes[]; };            // G: xx xy xz yy, yz zz

uint this_block();
uvec3 block_coordinates(uint key);

// The weight of a particle of radius r at offset d from it, and the weight's
// derivative by |d|^2 (both kernels reach REACH_RADII r: the spline's 2 h).
float weight(vec3 d, float r, out float slope)
{
    float d2 = dot(d, d);
    float reach2 = REACH_RADII * REACH_RADII * r * r;
    slope = 0.0;
    if (d2 >= reach2)
        return 0.0;
    if (kernel != 1) {   // Wyvill's soft objects: (1 - d^2 / R^2)^3
        float q = 1.0 - d2 / reach2;
        slope = -3.0 * q * q / reach2;
        return q * q * q;
    }
    // Cubic spline, 1 at the centre: q = |d| / r in [0, 2).
    float dist = sqrt(d2), q = dist / r;
    float dw_dq = q < 1.0 ? -3.0 * q + 2.25 * q * q : -0.75 * (2.0 - q) * (2.0 - q);
    float w = q < 1.0 ? 1.0 - 1.5 * q * q + 0.75 * q * q * q : 0.25 * (2.0 - q) * (2.0 - q) * (2.0 - q);
    slope = dist > 0.0 ? dw_dq / (r * 2.0 * dist) : 0.0;
    return w;
}

// The offset a particle's kernel sees: through its ellipsoid's G (shapes) for
// the anisotropic kernel, else the offset itself. grad_map: d(offset)/d(x)^T
// applied to a vector, here the same symmetric G.
vec3 kernel_offset(uint p, vec3 d, out mat3 g)
{
    if (kernel != 2) {
        g = mat3(1.0);
        return d;
    }
    vec4 a = shapes[2u * p], b = shapes[2u * p + 1u];
    g = mat3(a.x, a.y, a.z, a.y, a.w, b.x, a.z, b.x, b.y);
    return g * d;
}

// Adds the particles [first, last) to the sums of the sample at x.
void add_particles(uint first, uint last, vec3 x, inout float f, inout vec3 gradient, inout vec4 weighted,
                   inout float speed, inout float nearest, inout uint nearest_id)
{
    for (uint p = first; p < last; p++) {
        mat3 g;
        vec4 particle = particles[p];
        vec3 d = kernel_offset(p, x - particle.xyz, g);
        float d2 = dot(d, d);
        if (d2 < nearest) {
            nearest = d2;
            nearest_id = ids[p];
        }
        float slope;
        float w = weight(d, particle.w, slope);
        if (w <= 0.0)
            continue;
        f += w;
        gradient += 2.0 * slope * (g * d);
        vec4 a = attributes[p];
        weighted += w * a;
        speed += w * length(a.xyz);
    }
}

void main()
{
    uint block = this_block();
    if (block >= block_count)
        return;
    uvec3 base = block_coordinates(block_keys[block]) * BLOCK;
    for (uint s = gl_LocalInvocationID.x; s < BLOCK_SAMPLES; s += gl_WorkGroupSize.x) {
        uvec3 local = uvec3(s % (BLOCK + 1u), (s / (BLOCK + 1u)) % (BLOCK + 1u), s / ((BLOCK + 1u) * (BLOCK + 1u)));
        vec3 x = origin + vec3(base + local) * cell;
        ivec3 centre = ivec3(floor((x - origin) / bin));
        ivec3 lo = max(centre - 1, ivec3(0)), hi = min(centre + 1, ivec3(bins) - 1);
        float f = 0.0, speed = 0.0, nearest = 1.0 / 0.0;
        vec3 gradient = vec3(0.0);
        vec4 weighted = vec4(0.0);
        uint nearest_id = 0u;
        for (int z = lo.z; z <= hi.z; z++)
            for (int y = lo.y; y <= hi.y && lo.x <= hi.x; y++) {
                // A row of bins along x is one run of the sorted particles.
                uint row = bins.x * (uint(y) + bins.y * uint(z));
                add_particles(bin_starts[row + uint(lo.x)], bin_starts[row + uint(hi.x) + 1u], x, f, gradient,
                              weighted, speed, nearest, nearest_id);
            }
        uint slot = block * BLOCK_SAMPLES + s;
        field[slot] = vec4(gradient, f);
        sample_attributes[slot] = weighted;
        sample_extras[slot] = uvec2(floatBitsToUint(speed), nearest_id);
    }
}
