#version 450 core
// Per particle (Yu & Turk 2013, §4-5): the weighted mean and covariance of
// its neighbours within the support radius (weights w = 1 - (d / r_s)^3), the
// Laplacian-smoothed centre x + lambda (mean - x), and from the covariance's
// principal axes an ellipsoid of the sphere's volume: axes proportional to the
// eigenvalues, none shorter than the longest / k_r; a sphere at the particle's
// own position with fewer than N_eps neighbours, its smoothing faded out. Runs over the particles in cell order (neighbouring
// invocations read the same cells) and writes each one's ellipsoid at its
// draw slot. Parameters: anisotropy.h.

uint particle_invocation();
ivec3 cell_of(vec3 x);
uint cell_index(ivec3 c);
void symmetric_eigen(mat3 a, out vec3 values, out mat3 vectors);

layout(location = 0) uniform uint particle_count;
layout(location = 3) uniform ivec3 grid_cells;
layout(location = 4) uniform float support;        // r_s, world units
layout(location = 5) uniform uint min_neighbours;  // N_eps
layout(location = 6) uniform float lambda;         // centre smoothing
layout(location = 7) uniform float max_ratio;      // k_r

struct ellipsoid {
    vec4 centre_stretch;   // smoothed centre; longest axis in radii, 1 exactly for a sphere
    vec4 inverse_a;        // G xx, xy, xz, yy
    vec4 inverse_b;        // G yz, zz; neighbours; unused
};

layout(std430, binding = 1) readonly buffer CellStarts { uint cell_starts[]; };
layout(std430, binding = 3) readonly buffer Sorted { vec4 sorted[]; };
layout(std430, binding = 4) writeonly buffer Ellipsoids { ellipsoid ellipsoids[]; };

layout(local_size_x = 64) in;

// Weighted sums over the neighbours, of offsets from the particle itself:
// small numbers, so the covariance E[d d^T] - E[d] E[d]^T cancels little.
struct moments {
    float weight;
    vec3 first;
    vec3 diagonal;   // xx, yy, zz
    vec3 mixed;      // xy, xz, yz
    uint count;
};

void add_range(uint begin, uint end, vec3 x, inout moments m)
{
    float inverse_support = 1.0 / support;
    for (uint j = begin; j < end; j++) {
        vec3 d = sorted[j].xyz - x;
        float q = length(d) * inverse_support;
        if (q >= 1.0)
            continue;
        float w = 1.0 - q * q * q;
        m.weight += w;
        m.first += w * d;
        m.diagonal += w * d * d;
        m.mixed += w * vec3(d.x * d.y, d.x * d.z, d.y * d.z);
        m.count++;
    }
}

// The 27 cells around x as 9 rows of three consecutive cells.
moments gather(vec3 x)
{
    moments m = moments(0.0, vec3(0.0), vec3(0.0), vec3(0.0), 0u);
    ivec3 c = cell_of(x);
    int x0 = max(c.x - 1, 0), x1 = min(c.x + 1, grid_cells.x - 1);
    for (int z = max(c.z - 1, 0); z <= min(c.z + 1, grid_cells.z - 1); z++)
        for (int y = max(c.y - 1, 0); y <= min(c.y + 1, grid_cells.y - 1); y++)
            add_range(cell_starts[cell_index(ivec3(x0, y, z))], cell_starts[cell_index(ivec3(x1, y, z)) + 1u], x, m);
    return m;
}

// G = R diag(1 / s) R^T of the covariance's axes R and stretches s: the
// clamped eigenvalues (Yu & Turk eq. 15) scaled to a product of 1. Stretches
// are taken relative to the largest eigenvalue, which cannot underflow.
ellipsoid shape(vec3 centre, mat3 covariance, uint count)
{
    ellipsoid e = ellipsoid(vec4(centre, 1.0), vec4(1.0, 0.0, 0.0, 1.0), vec4(0.0, 1.0, float(count), 0.0));
    if (count < min_neighbours)
        return e;
    vec3 sigma;
    mat3 axes;
    symmetric_eigen(covariance, sigma, axes);
    if (!(sigma.x > 0.0))
        return e;
    vec2 rest = max(sigma.yz / sigma.x, vec2(1.0 / max_ratio));
    vec3 stretch = vec3(1.0, rest) / pow(rest.x * rest.y, 1.0 / 3.0);
    mat3 g = axes * mat3(1.0 / stretch.x, 0.0, 0.0, 0.0, 1.0 / stretch.y, 0.0, 0.0, 0.0, 1.0 / stretch.z) *
             transpose(axes);
    e.centre_stretch.w = stretch.x;
    e.inverse_a = vec4(g[0][0], g[0][1], g[0][2], g[1][1]);
    e.inverse_b.xy = vec2(g[1][2], g[2][2]);
    return e;
}

void main()
{
    uint k = particle_invocation();
    if (k >= particle_count)
        return;
    vec4 me = sorted[k];
    moments m = gather(me.xyz);
    // The particle itself is among its neighbours: the weight is at least 1.
    vec3 mean = m.first / m.weight;
    vec3 diagonal = m.diagonal / m.weight - mean * mean;
    vec3 mixed = m.mixed / m.weight - vec3(mean.x * mean.y, mean.x * mean.z, mean.y * mean.z);
    mat3 covariance = mat3(diagonal.x, mixed.x, mixed.y, mixed.x, diagonal.y, mixed.z, mixed.y, mixed.z, diagonal.z);
    // The smoothing fades out below N_eps neighbours: pulled fully towards a
    // mean of a few neighbours, the particles of a jet or a thin sheet move
    // apart as often as together and their spheres part (a jittered row fell
    // into 4 pieces); not pulled at all, a ball's edge particles stand out of
    // their flattened neighbours as separate beads.
    float pull = lambda * min(1.0, float(m.count) / float(min_neighbours));
    vec3 centre = me.xyz + pull * mean;
    ellipsoids[floatBitsToUint(me.w)] = shape(centre, covariance, m.count);
}
