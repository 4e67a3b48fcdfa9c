#version 450 core
// One 1-D pass of the separable bilateral Gaussian (Janisz 2012, §4.1.2.1,
// eqs. 4.1-4.3): a Gaussian in space times a Gaussian in depth, applied along
// x and then y as if it were separable, the approximation the thesis finds good
// enough for real time. Background pixels stay as they are.
//
// Two changes make the approximation hold up on real fluid:
//  - Samples beyond a depth jump get no weight at all (surface_walk), so
//    separate surfaces never blend, whatever the range Gaussian says.
//  - The range Gaussian measures depth from the plane through the centre with
//    the surface's slope along the pass, not from the centre's depth. On a
//    surface seen at a grazing angle depth changes by about a particle radius
//    per pixel; measured from the centre, the range weights would smooth only
//    across the slope, never along it, and a separable filter turns that into
//    stripes. Measured from the plane, they weigh down only real bumps. The
//    weighted mean is likewise taken of the samples' offsets from that plane:
//    a plane, tilted or not, then stays exactly where it is even where a
//    silhouette or the image's edge empties one side of the kernel, where a
//    plain mean would drag the edge along the slope.

struct surface_walk {
    float last;
    bool ended;
};
surface_walk walk_from(float z);
bool walk_accepts(inout surface_walk walk, float zi);
float depth_at(ivec2 p);
int kernel_radius(float z);

layout(location = 0) uniform ivec2 axis;
layout(location = 2) uniform float particle_radius;

layout(location = 0) out float depth_out;

// Spatially weighted sums over the samples on the centre's surface on one side.
struct side_moments {
    float weight;
    float depth;    // sum of weight * depth
    float offset;   // sum of weight * distance from the centre
};

side_moments side_of(ivec2 p, float z, int radius, int direction, float inv_two_space)
{
    side_moments m = side_moments(0.0, 0.0, 0.0);
    surface_walk walk = walk_from(z);
    for (int i = 1; i <= radius && !walk.ended; i++) {
        float zi = depth_at(p + direction * i * axis);
        if (!walk_accepts(walk, zi))
            continue;
        float g = exp(-float(i * i) * inv_two_space);
        m.weight += g;
        m.depth += g * zi;
        m.offset += g * float(i);
    }
    return m;
}

// Depth change per pixel along +axis: between the weighted means of the two
// sides, or between the centre and the one side a silhouette leaves.
float slope_along_axis(float z, side_moments forward, side_moments backward)
{
    bool has_forward = forward.weight > 0.0, has_backward = backward.weight > 0.0;
    if (has_forward && has_backward)
        return (forward.depth / forward.weight - backward.depth / backward.weight) /
               (forward.offset / forward.weight + backward.offset / backward.weight);
    if (has_forward)
        return (forward.depth / forward.weight - z) / (forward.offset / forward.weight);
    if (has_backward)
        return (z - backward.depth / backward.weight) / (backward.offset / backward.weight);
    return 0.0;
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = depth_at(p);
    if (z <= 0.0) {
        depth_out = z;
        return;
    }
    int radius = kernel_radius(z);
    // The kernel ends at three spatial sigmas, where the Gaussian is ~1 %.
    float sigma_space = float(radius) / 3.0;
    // Bumps between the spheres of one surface are a fraction of a radius:
    // a range sigma of one radius smooths them and keeps larger features.
    float sigma_range = particle_radius;
    float inv_two_space = 0.5 / (sigma_space * sigma_space);
    float inv_two_range = 0.5 / (sigma_range * sigma_range);

    float slope = slope_along_axis(z, side_of(p, z, radius, 1, inv_two_space), side_of(p, z, radius, -1, inv_two_space));
    float off_plane_sum = 0.0, weight_sum = 1.0;   // the centre lies on the plane
    for (int direction = -1; direction <= 1; direction += 2) {
        surface_walk walk = walk_from(z);
        for (int i = 1; i <= radius && !walk.ended; i++) {
            float zi = depth_at(p + direction * i * axis);
            if (!walk_accepts(walk, zi))
                continue;
            float off_plane = zi - (z + slope * float(direction * i));
            float w = exp(-float(i * i) * inv_two_space - off_plane * off_plane * inv_two_range);
            off_plane_sum += w * off_plane;
            weight_sum += w;
        }
    }
    depth_out = z + off_plane_sum / weight_sum;
}
