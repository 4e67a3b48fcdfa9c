// mesh_openvdb.cpp — the OpenVDB side of bench/peer/mesh_vs_openvdb.sh (issue 27):
// the industry's way to mesh particles, with Debian's libopenvdb-dev, and the
// distance between two meshes.
//
//   mesh_openvdb mesh IN.f32 RADIUS CELL OUT.ply [GROW]
//       the particles of IN.f32 (float32 x y z) as spheres of RADIUS
//       (ParticlesToLevelSet, a narrow-band level set of voxel size CELL, world
//       units), polygonised at level 0 (VolumeToMesh, quads split into
//       triangles); writes OUT.ply (binary, x y z, triangles) and prints
//       "openvdb: P particles, T triangles, S s (L s level set, M s mesh)".
//       With GROW > 0 the spheres are (1 + GROW) x RADIUS, the level set is
//       rebuilt as a signed distance (levelSetRebuild) and meshed GROW x RADIUS
//       inside: how an OpenVDB user closes the gaps between particles at rest
//       (spheres of the solver's radius, half the spacing, barely touch and
//       leave a cavity in every lattice cube) and keeps a lone particle at its
//       radius.
//   mesh_openvdb distance A.ply B.ply
//       for every vertex of A the nearest vertex of B and the other way round;
//       prints "distance: mean M max X (A->B mean, max; B->A mean, max)".
//
// Reads the binary little-endian PLY that fluidcast mesh and this program
// write: 4-byte vertex properties, x y z first; faces as uchar-counted uint lists.
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Mesh {
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
};

// ParticlesToLevelSet's particle list: positions, one radius for all.
struct Particles {
    using PosType = openvdb::Vec3R;
    std::vector<openvdb::Vec3R> positions;
    double radius = 0;
    size_t size() const { return positions.size(); }
    void getPos(size_t n, openvdb::Vec3R &xyz) const { xyz = positions[n]; }
    void getPosRad(size_t n, openvdb::Vec3R &xyz, openvdb::Real &r) const
    {
        xyz = positions[n];
        r = radius;
    }
};

double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<openvdb::Vec3R> read_f32(const char *path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error(std::string("cannot open ") + path);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() % 12 != 0)
        throw std::runtime_error(std::string(path) + ": not a whole number of float32 x y z triples");
    std::vector<openvdb::Vec3R> out(bytes.size() / 12);
    for (size_t i = 0; i < out.size(); i++) {
        float p[3];
        std::memcpy(p, bytes.data() + 12 * i, 12);
        out[i] = openvdb::Vec3R(p[0], p[1], p[2]);
    }
    return out;
}

Mesh read_ply(const char *path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error(std::string("cannot open ") + path);
    std::string line;
    size_t vertices = 0, faces = 0, properties = 0;
    bool in_vertex = false;
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream words(line);
        std::string first, second, third;
        words >> first >> second >> third;
        if (first == "element") {
            in_vertex = second == "vertex";
            (in_vertex ? vertices : faces) = std::stoul(third);
        } else if (first == "property" && in_vertex) {
            properties++;
        }
    }
    Mesh m;
    std::vector<float> record(properties);
    for (size_t i = 0; i < vertices; i++) {
        in.read(reinterpret_cast<char *>(record.data()), 4 * properties);
        m.points.emplace_back(record[0], record[1], record[2]);
    }
    for (size_t i = 0; i < faces; i++) {
        uint8_t n = 0;
        uint32_t idx[3];
        in.read(reinterpret_cast<char *>(&n), 1);
        if (n != 3)
            throw std::runtime_error(std::string(path) + ": a face that is not a triangle");
        in.read(reinterpret_cast<char *>(idx), 12);
        m.triangles.emplace_back(idx[0], idx[1], idx[2]);
    }
    if (!in)
        throw std::runtime_error(std::string(path) + ": truncated");
    return m;
}

void write_ply(const char *path, const Mesh &m)
{
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\ncomment OpenVDB ParticlesToLevelSet + VolumeToMesh\n"
        << "element vertex " << m.points.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
        << "element face " << m.triangles.size() << "\nproperty list uchar uint vertex_indices\nend_header\n";
    for (const auto &p : m.points)
        out.write(reinterpret_cast<const char *>(p.asPointer()), 12);
    for (const auto &t : m.triangles) {
        const uint8_t three = 3;
        out.write(reinterpret_cast<const char *>(&three), 1);
        out.write(reinterpret_cast<const char *>(t.asPointer()), 12);
    }
    if (!out)
        throw std::runtime_error(std::string("cannot write ") + path);
}

int mesh_particles(const char *input, double radius, double cell, double grow, const char *output)
{
    Particles particles;
    particles.positions = read_f32(input);
    particles.radius = radius * (1.0 + grow);
    auto start = std::chrono::steady_clock::now();
    auto grid = openvdb::createLevelSet<openvdb::FloatGrid>(cell, 3.0);
    openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
    raster.setRmin(0.0);   // the default (1.5 voxels) drops every particle at cells of 1 x r and coarser
    raster.rasterizeSpheres(particles);
    raster.finalize(true);
    // Grown spheres' union is a signed distance only near its surface (inside, each voxel holds its depth in
    // the nearest sphere); rebuilt, it is one deep enough to mesh grow x radius further in.
    float level = 0.0f;
    if (grow > 0.0) {
        level = static_cast<float>(-grow * radius);
        float inside = static_cast<float>(grow * radius / cell) + 3.0f;
        grid = openvdb::tools::levelSetRebuild(*grid, 0.0f, 3.0f, inside);
    }
    double level_set_s = seconds_since(start);
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    auto mesh_start = std::chrono::steady_clock::now();
    openvdb::tools::volumeToMesh(*grid, points, triangles, quads, level);
    Mesh m{points, triangles};
    // OpenVDB's quads and triangles wind the other way round from fluidcast's (outward, counter-clockwise).
    for (auto &t : m.triangles)
        std::swap(t[1], t[2]);
    for (const auto &q : quads) {
        m.triangles.emplace_back(q[0], q[2], q[1]);
        m.triangles.emplace_back(q[0], q[3], q[2]);
    }
    double mesh_s = seconds_since(mesh_start), total_s = seconds_since(start);
    write_ply(output, m);
    std::printf("openvdb: %zu particles, %zu triangles, %.3f s (%.3f s level set, %.3f s mesh)\n",
                particles.size(), m.triangles.size(), total_s, level_set_s, mesh_s);
    return 0;
}

// Nearest vertex of `to` for each vertex of `from`, through a k-d tree of
// `to` (a hash grid's shells, used before, took hours where one mesh has
// surfaces far from the other's, as OpenVDB's cavities are from a closed mesh).
struct Distances {
    double mean = 0, max = 0;
};

class KdTree {
public:
    explicit KdTree(const std::vector<openvdb::Vec3s> &points) : points_(points), order_(points.size())
    {
        for (size_t i = 0; i < order_.size(); i++)
            order_[i] = i;
        build(0, order_.size(), 0);
    }

    double nearest(const openvdb::Vec3s &p) const
    {
        double best = INFINITY;
        search(p, 0, order_.size(), 0, best);
        return std::sqrt(best);
    }

private:
    // order_[begin, end) split at its middle along `axis`: the median there, smaller before, larger after.
    void build(size_t begin, size_t end, int axis)
    {
        if (end - begin < 2)
            return;
        size_t mid = begin + (end - begin) / 2;
        std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                         [&](size_t a, size_t b) { return points_[a][axis] < points_[b][axis]; });
        build(begin, mid, (axis + 1) % 3);
        build(mid + 1, end, (axis + 1) % 3);
    }

    void search(const openvdb::Vec3s &p, size_t begin, size_t end, int axis, double &best) const
    {
        if (begin >= end)
            return;
        size_t mid = begin + (end - begin) / 2;
        const openvdb::Vec3s &q = points_[order_[mid]];
        best = std::min(best, (double)(q - p).lengthSqr());
        double side = (double)p[axis] - q[axis];
        int next = (axis + 1) % 3;
        // The half holding p first; the other only if the splitting plane is nearer than the best so far.
        if (side < 0) {
            search(p, begin, mid, next, best);
            if (side * side < best)
                search(p, mid + 1, end, next, best);
        } else {
            search(p, mid + 1, end, next, best);
            if (side * side < best)
                search(p, begin, mid, next, best);
        }
    }

    const std::vector<openvdb::Vec3s> &points_;
    std::vector<size_t> order_;
};

Distances nearest_vertex(const Mesh &from, const Mesh &to)
{
    KdTree tree(to.points);
    Distances d;
    for (const auto &p : from.points) {
        double best = tree.nearest(p);
        d.mean += best;
        d.max = std::max(d.max, best);
    }
    d.mean /= std::max<size_t>(1, from.points.size());
    return d;
}

int distance(const char *a_path, const char *b_path)
{
    Mesh a = read_ply(a_path), b = read_ply(b_path);
    if (a.points.empty() || b.points.empty())
        throw std::runtime_error("a mesh without vertices");
    Distances ab = nearest_vertex(a, b), ba = nearest_vertex(b, a);
    double mean = (ab.mean * a.points.size() + ba.mean * b.points.size()) / (a.points.size() + b.points.size());
    std::printf("distance: mean %.6g max %.6g (A->B mean %.6g max %.6g; B->A mean %.6g max %.6g)\n", mean,
                std::max(ab.max, ba.max), ab.mean, ab.max, ba.mean, ba.max);
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    try {
        openvdb::initialize();
        if ((argc == 6 || argc == 7) && std::strcmp(argv[1], "mesh") == 0)
            return mesh_particles(argv[2], std::stod(argv[3]), std::stod(argv[4]), argc == 7 ? std::stod(argv[6]) : 0.0,
                                  argv[5]);
        if (argc == 4 && std::strcmp(argv[1], "distance") == 0)
            return distance(argv[2], argv[3]);
        std::fprintf(stderr, "usage: %s mesh IN.f32 RADIUS CELL OUT.ply [GROW] | distance A.ply B.ply\n", argv[0]);
        return 2;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mesh_openvdb: %s\n", e.what());
        return 1;
    }
}
