#version 450 core
// The particles' field of a surface mesh (surface_mesher.c): a compute
// library without main, linked into the field pass (the field's value at the
// blocks' samples) and the edges pass (the field's gradient and the particles'
// attributes at each vertex, where they are wanted, not at every sample).
// A point sums the particles of the bins within BIN_SPLIT of its own (the particles
// come sorted by bin, surface_grid.h) in bin order, so equal input gives
// equal bits, and a sample shared by two blocks gets the same value in both:
// its bins and their order follow from its lattice point alone.
// METABALL_REACH_RADII, SPH_REACH_RADII, BIN_SPLIT and MISSING come as #defines
// (FC_SURFACE_GRID, surface_passes.c; the reaches from surface_mesher.h).

layout(location = 1) uniform vec3 origin;  // world position of lattice point 0, where bin 0 starts
layout(location = 4) uniform int kernel;   // fc_surface_kernel: 0 metaball, 1 sph (2 is 0 on ellipsoids)
layout(location = 6) uniform float bin;    // bin edge, at least the field's reach / BIN_SPLIT
layout(location = 7) uniform uvec3 bins;   // bins along each axis

layout(std430, binding = 0) readonly buffer Particles { vec4 particles[]; };      // xyz, radius; by bin
layout(std430, binding = 1) readonly buffer Attributes { vec4 attributes[]; };    // velocity, density
layout(std430, binding = 2) readonly buffer Ids { uint ids[]; };
layout(std430, binding = 4) readonly buffer BinStarts { uint bin_starts[]; };   // x + bins.x (y + bins.y z)
layout(std430, binding = 9) readonly buffer Shapes { vec4 shapes[]; };            // G: xx xy xz yy, yz zz

// The weight of a particle of radius r at offset d from it, and the weight's
// derivative by |d|^2 (kernel_weight in surface_mesher.c: the
// metaballs reach METABALL_REACH_RADII r, the spline SPH_REACH_RADII r = 2 h).
float weight(vec3 d, float r, out float slope)
{
    float d2 = dot(d, d);
    float reach = (kernel == 1 ? SPH_REACH_RADII : METABALL_REACH_RADII) * r, reach2 = reach * reach;
    slope = 0.0;
    if (d2 >= reach2)
        return 0.0;
    if (kernel != 1) {   // Wyvill's soft objects: (1 - d^2 / R^2)^3
        float q = 1.0 - d2 / reach2;
        slope = -3.0 * q * q / reach2;
        return q * q * q;
    }
    // Cubic spline, 1 at the centre: q = |d| / h in [0, 2).
    float h = 0.5 * reach, dist = sqrt(d2), q = dist / h;
    float dw_dq = q < 1.0 ? -3.0 * q + 2.25 * q * q : -0.75 * (2.0 - q) * (2.0 - q);
    float w = q < 1.0 ? 1.0 - 1.5 * q * q + 0.75 * q * q * q : 0.25 * (2.0 - q) * (2.0 - q) * (2.0 - q);
    slope = dist > 0.0 ? dw_dq / (h * 2.0 * dist) : 0.0;
    return w;
}

// The ellipsoid's G of particle p for the anisotropic kernel, else identity.
mat3 shape_of(uint p)
{
    if (kernel != 2)
        return mat3(1.0);
    vec4 a = shapes[2u * p], b = shapes[2u * p + 1u];
    return mat3(a.x, a.y, a.z, a.y, a.w, b.x, a.z, b.x, b.y);
}

// The bin x lies in, unclamped (a sample may lie past the last bin).
ivec3 bin_of(vec3 x)
{
    return ivec3(floor((x - origin) / bin));
}

// The bins around x: [lo, hi] per axis, empty where lo > hi.
void bins_around(vec3 x, out ivec3 lo, out ivec3 hi)
{
    ivec3 centre = bin_of(x);
    lo = max(centre - int(BIN_SPLIT), ivec3(0));
    hi = min(centre + int(BIN_SPLIT), ivec3(bins) - 1);
}

// The run of sorted particles of the row of bins lo.x..hi.x at (y, z).
uvec2 row_run(ivec3 lo, ivec3 hi, int y, int z)
{
    uint row = bins.x * (uint(y) + bins.y * uint(z));
    return uvec2(bin_starts[row + uint(lo.x)], bin_starts[row + uint(hi.x) + 1u]);
}

// The run of row (y, z)'s particles, of the bins lo.x..hi.x, that x's field
// may reach, `at` being x in bins ((x - origin) / bin, bin_of's expression).
// The field reaches at most BIN_SPLIT bins (the grid's reach / bin <= BIN_SPLIT
// / 1.001, surface_grid.c), so a bin farther from x than that, 1% more for
// rounding, holds only particles whose weight at x is 0: dropping them from the
// ends of the row leaves the sum's bits as they were and skips most of the
// corners of the (2 BIN_SPLIT + 1)^3 bins.
uvec2 reached_run(vec3 at, ivec3 lo, ivec3 hi, int y, int z)
{
    float cut = float(BIN_SPLIT) * 1.01;
    float dy = max(max(float(y) - at.y, at.y - float(y + 1)), 0.0);
    float dz = max(max(float(z) - at.z, at.z - float(z + 1)), 0.0);
    float rest = cut * cut - dy * dy - dz * dz;
    if (rest <= 0.0)
        return uvec2(0u);
    float s = sqrt(rest);
    int x0 = max(lo.x, int(floor(at.x - s))), x1 = min(hi.x, int(floor(at.x + s)));
    return x0 <= x1 ? row_run(ivec3(x0), ivec3(x1), y, z) : uvec2(0u);
}

// The field at x: the value only, as the samples need it.
float field_value(vec3 x)
{
    ivec3 lo, hi;
    bins_around(x, lo, hi);
    vec3 at = (x - origin) / bin;
    float f = 0.0, slope;
    for (int z = lo.z; z <= hi.z; z++)
        for (int y = lo.y; y <= hi.y && lo.x <= hi.x; y++) {
            uvec2 run = reached_run(at, lo, hi, y, z);
            for (uint p = run.x; p < run.y; p++) {
                vec4 particle = particles[p];
                vec3 d = x - particle.xyz;
                f += weight(kernel == 2 ? shape_of(p) * d : d, particle.w, slope);
            }
        }
    return f;
}

// The particles of the bins [lo, hi] (clamped to the grid's): at most this many terms in the field
// of a point whose bins_around lie within them.
uint particles_in(ivec3 lo, ivec3 hi)
{
    lo = max(lo, ivec3(0));
    hi = min(hi, ivec3(bins) - 1);
    uint n = 0u;
    for (int z = lo.z; z <= hi.z; z++)
        for (int y = lo.y; y <= hi.y && lo.x <= hi.x; y++) {
            uvec2 run = row_run(lo, hi, y, z);
            n += run.y - run.x;
        }
    return n;
}

// The sum of the weights at x of the particles p0 <= p < p1, added to f
// until it reaches `threshold`.
float add_weights(vec3 x, uint p0, uint p1, float f, float threshold)
{
    float slope;
    for (uint p = p0; p < p1 && f < threshold; p++) {
        vec4 particle = particles[p];
        vec3 d = x - particle.xyz;
        f += weight(kernel == 2 ? shape_of(p) * d : d, particle.w, slope);
    }
    return f;
}

// Whether the field at x reaches `threshold`: field_value's terms, the 3^3
// bins next to x's own first (where the nearest particles lie: inside a body of
// fluid they alone reach it), then the rest, stopping once the sum does. Every
// weight is at least 0 and the order differs from field_value's, so the two
// sums differ by rounding alone: `threshold` carries the margin for it
// (surface_field.comp.glsl).
bool field_reaches(vec3 x, float threshold)
{
    ivec3 centre = bin_of(x), lo, hi;
    bins_around(x, lo, hi);
    ivec3 near_lo = max(lo, centre - 1), near_hi = min(hi, centre + 1);
    const ivec2 near_rows[9] = ivec2[9](ivec2(0, 0), ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1),
                                        ivec2(-1, -1), ivec2(1, -1), ivec2(-1, 1), ivec2(1, 1));
    float f = 0.0;
    for (int k = 0; k < 9 && f < threshold && near_lo.x <= near_hi.x; k++) {
        int y = centre.y + near_rows[k].x, z = centre.z + near_rows[k].y;
        if (y < near_lo.y || y > near_hi.y || z < near_lo.z || z > near_hi.z)
            continue;
        uvec2 run = row_run(near_lo, near_hi, y, z);
        f = add_weights(x, run.x, run.y, f, threshold);
    }
    for (int z = lo.z; z <= hi.z && f < threshold; z++)
        for (int y = lo.y; y <= hi.y && lo.x <= hi.x; y++) {
            bool near_row = abs(z - centre.z) <= 1 && abs(y - centre.y) <= 1 && near_lo.x <= near_hi.x;
            if (!near_row) {
                uvec2 run = row_run(lo, hi, y, z);
                f = add_weights(x, run.x, run.y, f, threshold);
                continue;
            }
            uvec2 below = row_run(lo, ivec3(near_lo.x - 1), y, z);   // the row's bins below the near ones
            uvec2 above = row_run(ivec3(near_hi.x + 1), hi, y, z);   // and above them
            if (lo.x < near_lo.x)
                f = add_weights(x, below.x, below.y, f, threshold);
            if (near_hi.x < hi.x)
                f = add_weights(x, above.x, above.y, f, threshold);
        }
    return f >= threshold;
}

// The field's gradient at x: all a vertex takes when the frame has no
// attributes.
vec3 field_gradient(vec3 x)
{
    ivec3 lo, hi;
    bins_around(x, lo, hi);
    vec3 gradient = vec3(0.0);
    for (int z = lo.z; z <= hi.z; z++)
        for (int y = lo.y; y <= hi.y && lo.x <= hi.x; y++) {
            uvec2 run = row_run(lo, hi, y, z);
            for (uint p = run.x; p < run.y; p++) {
                vec4 particle = particles[p];
                mat3 g = shape_of(p);
                vec3 d = kernel == 2 ? g * (x - particle.xyz) : x - particle.xyz;
                float slope;
                if (weight(d, particle.w, slope) > 0.0)
                    gradient += 2.0 * slope * (kernel == 2 ? g * d : d);
            }
        }
    return gradient;
}

// The particle nearest x among the bins read around it (MISSING if none):
// where no particle's field reaches a vertex (a kernel's support can end
// between an edge's two samples), its normal points away from this one and
// its attributes are this one's.
uint nearest_particle(vec3 x)
{
    ivec3 lo, hi;
    bins_around(x, lo, hi);
    float nearest = 1.0 / 0.0;
    uint found = MISSING;
    for (int z = lo.z; z <= hi.z; z++)
        for (int y = lo.y; y <= hi.y && lo.x <= hi.x; y++) {
            uvec2 run = row_run(lo, hi, y, z);
            for (uint p = run.x; p < run.y; p++) {
                vec3 d = x - particles[p].xyz;
                if (dot(d, d) < nearest) {
                    nearest = dot(d, d);
                    found = p;
                }
            }
        }
    return found;
}

// Everything a vertex at x takes: the field's gradient, the particles'
// attributes averaged with the field's weights (velocity and density, and
// speed; the nearest particle's where no field reaches x), and the nearest
// particle's id.
void field_at_vertex(vec3 x, out vec3 gradient, out vec4 mean, out float speed, out uint nearest_id)
{
    ivec3 lo, hi;
    bins_around(x, lo, hi);
    float f = 0.0, nearest = 1.0 / 0.0;
    vec4 weighted = vec4(0.0);
    gradient = vec3(0.0);
    speed = 0.0;
    nearest_id = 0u;
    for (int z = lo.z; z <= hi.z; z++)
        for (int y = lo.y; y <= hi.y && lo.x <= hi.x; y++) {
            uvec2 run = row_run(lo, hi, y, z);
            for (uint p = run.x; p < run.y; p++) {
                mat3 g = shape_of(p);
                vec3 d = g * (x - particles[p].xyz);
                float d2 = dot(d, d), slope;
                if (d2 < nearest) {
                    nearest = d2;
                    nearest_id = ids[p];
                }
                float w = weight(d, particles[p].w, slope);
                if (w <= 0.0)
                    continue;
                f += w;
                gradient += 2.0 * slope * (g * d);
                vec4 a = attributes[p];
                weighted += w * a;
                speed += w * length(a.xyz);
            }
        }
    mean = weighted / max(f, 1e-30);
    speed /= max(f, 1e-30);
    uint p = f > 0.0 ? MISSING : nearest_particle(x);
    if (p != MISSING) {
        mean = attributes[p];
        speed = length(mean.xyz);
    }
}
