#include "planner/layers/slice.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>

namespace fibrecell::planner {

// Degenerate positions (the plane through a vertex, along an edge, containing a face) are resolved
// by symbolic perturbation: the plane is taken an infinitesimal step below z, so a vertex with
// z_v == z (within the snap tolerance) lies above it. Every vertex is classified once, so
// neighbouring tets agree. A section point on an edge (a below, b above) is keyed by the edge, or
// by b itself when b lies on the plane (the perturbed point converges to b); so points are shared
// between all tets around an edge or vertex, and the section is conforming. A tet whose section
// collapses (two points keyed by the same vertex) loses those duplicates, and one that collapses to
// a segment or point gives no triangle. Orientation comes from the tet's orientation, not from a
// rounded area, so it is consistent across neighbours.

namespace {

// Faces opposite each local vertex, counter-clockwise seen from outside a positive tet.
constexpr int kFaceOpposite[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

enum Side : std::uint8_t { below, on, above };

// Section points by key: an open-addressing table cleared per layer in O(expected points).
class PointTable {
  public:
    void reset(std::size_t expected) {
        const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(16, 2 * expected));
        keys_.assign(capacity, kEmpty);
        size_ = 0;
        values_.resize(capacity);
        shift_ = 64 - std::countr_zero(capacity);
    }
    // The id stored for `key`, or the result of add() stored under it.
    template <class Add>
    int find_or_add(std::uint64_t key, Add add) {
        std::size_t slot = (key * 0x9E3779B97F4A7C15ull) >> shift_;
        const std::size_t mask = keys_.size() - 1;
        while (keys_[slot] != kEmpty) {
            if (keys_[slot] == key) return values_[slot];
            slot = (slot + 1) & mask;
        }
        if ((size_ + 1) * 2 > keys_.size()) {  // keep the load at most 1/2
            grow();
            return find_or_add(key, add);
        }
        ++size_;
        keys_[slot] = key;
        return values_[slot] = add();
    }

  private:
    static constexpr std::uint64_t kEmpty = ~0ull;
    void grow() {
        std::vector<std::uint64_t> keys = std::move(keys_);
        std::vector<int> values = std::move(values_);
        reset(keys.size());
        for (std::size_t i = 0; i < keys.size(); ++i)
            if (keys[i] != kEmpty) find_or_add(keys[i], [&] { return values[i]; });
    }
    std::vector<std::uint64_t> keys_;
    std::vector<int> values_;
    std::size_t size_ = 0;
    int shift_ = 60;
};

std::uint64_t vertex_key(int v) {
    return static_cast<std::uint64_t>(v) << 32 | static_cast<std::uint32_t>(v);
}
std::uint64_t edge_key(int a, int b) {
    if (a > b) std::swap(a, b);
    return static_cast<std::uint64_t>(a) << 32 | static_cast<std::uint32_t>(b);
}

bool is_odd_permutation(const int (&p)[4]) {
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j];
    return inversions % 2 == 1;
}

double doubled_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Six times the signed volume of a tet, in plain arithmetic (this runs once per cut tet).
double orientation(const TetMesh& mesh, const Tet& t) {
    const double* p0 = mesh.vertices[t[0]].data();
    double d[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) d[r][c] = mesh.vertices[t[r + 1]][c] - p0[c];
    return d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) -
           d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0]) +
           d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
}

double squared_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const double dx = a.x() - b.x(), dy = a.y() - b.y();
    return dx * dx + dy * dy;
}

int find_root(std::vector<int>& parent, int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// Merges points closer than `tolerance`, drops triangles that collapse or have no positive area,
// and drops points no triangle uses. Merging keeps the lower id, so neighbours stay conforming.
void clean_up(LayerMesh& layer, double tolerance) {
    const double tolerance2 = tolerance * tolerance;
    std::vector<int> parent;
    for (const auto& tri : layer.triangles) {
        for (int e = 0; e < 3; ++e) {
            const int u = tri[e], v = tri[(e + 1) % 3];
            if (squared_distance(layer.vertices[u], layer.vertices[v]) > tolerance2) continue;
            if (parent.empty()) {
                parent.resize(layer.vertices.size());
                std::iota(parent.begin(), parent.end(), 0);
            }
            const int ru = find_root(parent, u), rv = find_root(parent, v);
            parent[std::max(ru, rv)] = std::min(ru, rv);
        }
    }
    std::size_t kept = 0;
    for (std::size_t f = 0; f < layer.triangles.size(); ++f) {
        std::array<int, 3> tri = layer.triangles[f];
        if (!parent.empty())
            for (int& v : tri) v = find_root(parent, v);
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) continue;
        if (doubled_area(layer.vertices[tri[0]], layer.vertices[tri[1]], layer.vertices[tri[2]]) <=
            0)
            continue;  // a numerically flat tet's sliver
        layer.triangles[kept] = tri;
        layer.triangle_tet[kept] = layer.triangle_tet[f];
        ++kept;
    }
    layer.triangles.resize(kept);
    layer.triangle_tet.resize(kept);

    std::vector<int> new_id(layer.vertices.size(), -1);
    for (const auto& tri : layer.triangles)
        for (int v : tri) new_id[v] = 0;
    int next = 0;
    for (std::size_t v = 0; v < new_id.size(); ++v) {
        if (new_id[v] < 0) continue;
        new_id[v] = next;
        layer.vertices[next++] = layer.vertices[v];
    }
    layer.vertices.resize(next);
    for (auto& tri : layer.triangles)
        for (int& v : tri) v = new_id[v];
}

void check_slice_inputs(double z, const SliceOptions& options) {
    if (!std::isfinite(z))
        throw std::invalid_argument("slice: plane height z is not finite: " + std::to_string(z));
    if (!std::isfinite(options.snap_tolerance) || options.snap_tolerance < 0)
        throw std::invalid_argument("slice: snap_tolerance must be >= 0, got " +
                                    std::to_string(options.snap_tolerance));
}

}  // namespace

LayerMesh slice_tet_mesh(const TetMesh& mesh, const SliceIndex& index, double z,
                         const SliceOptions& options) {
    check_slice_inputs(z, options);
    if (index.tet_z_min.size() != mesh.tets.size())
        throw std::invalid_argument("slice: the index was built for " +
                                    std::to_string(index.tet_z_min.size()) +
                                    " tets, the mesh has " + std::to_string(mesh.tets.size()));
    const double tolerance = options.snap_tolerance * index.size;
    const double z_low = z - tolerance;  // below: z_v < z_low; on: z_v <= z + tolerance

    LayerMesh layer;
    layer.z = z;
    const std::span<const int> near = index.tets_near(z_low);
    PointTable points;
    points.reset(near.size());
    const int vertex_count = static_cast<int>(mesh.vertices.size());

    for (const int ti : near) {
        if (!(index.tet_z_min[ti] < z_low && index.tet_z_max[ti] >= z_low)) continue;
        const Tet& tet = mesh.tets[ti];
        Side side[4];
        int below_count = 0;
        for (int i = 0; i < 4; ++i) {
            if (tet[i] < 0 || tet[i] >= vertex_count)
                throw std::invalid_argument("slice: tet " + std::to_string(ti) + " uses vertex " +
                                            std::to_string(tet[i]) + " of " +
                                            std::to_string(vertex_count));
            const double zv = mesh.vertices[tet[i]].z();
            side[i] = zv < z_low ? below : (zv <= z + tolerance ? on : above);
            below_count += side[i] == below;
        }
        if (orientation(mesh, tet) <= 0)
            throw std::invalid_argument("slice: tet " + std::to_string(ti) +
                                        " is not positively oriented");

        // The section point on local edge (lo below, hi on or above the plane).
        auto point = [&](int lo, int hi) {
            const int a = tet[lo], b = tet[hi];
            if (side[hi] == on)
                return points.find_or_add(vertex_key(b), [&] {
                    layer.vertices.emplace_back(mesh.vertices[b].x(), mesh.vertices[b].y());
                    return static_cast<int>(layer.vertices.size()) - 1;
                });
            return points.find_or_add(edge_key(a, b), [&] {
                const Eigen::Vector3d& pa = mesh.vertices[a];
                const Eigen::Vector3d& pb = mesh.vertices[b];
                const double t = (z - pa.z()) / (pb.z() - pa.z());
                layer.vertices.emplace_back(pa.x() + t * (pb.x() - pa.x()),
                                            pa.y() + t * (pb.y() - pa.y()));
                return static_cast<int>(layer.vertices.size()) - 1;
            });
        };

        int ring[4];  // the section polygon, counter-clockwise seen from +z
        int ring_size = 0;
        if (below_count == 1 || below_count == 3) {
            // One vertex alone on its side: a triangle on the edges from it.
            const Side alone = below_count == 1 ? below : above;
            int i = 0;
            while ((side[i] == below) != (alone == below)) ++i;
            const int* f = kFaceOpposite[i];
            if (below_count == 1) {
                for (int k = 0; k < 3; ++k) ring[k] = point(i, f[k]);
            } else {  // from +z the face is seen from the lone vertex's side: reverse it
                for (int k = 0; k < 3; ++k) ring[k] = point(f[(3 - k) % 3], i);
            }
            ring_size = 3;
        } else {
            // Two and two: a quad. With (a1, a2, b1, b2) an even permutation of the tet,
            // p(a1,b1) p(a1,b2) p(a2,b2) p(a2,b1) runs counter-clockwise seen from +z.
            int order[4], n_below = 0, n_above = 2;
            for (int i = 0; i < 4; ++i) order[side[i] == below ? n_below++ : n_above++] = i;
            if (is_odd_permutation(order)) std::swap(order[2], order[3]);
            const int a1 = order[0], a2 = order[1], b1 = order[2], b2 = order[3];
            const int quad[4] = {point(a1, b1), point(a1, b2), point(a2, b2), point(a2, b1)};
            for (int q = 0; q < 4; ++q)  // points keyed by the same vertex collapse
                if (quad[q] != quad[(q + 3) % 4]) ring[ring_size++] = quad[q];
        }

        if (ring_size == 3) {
            layer.triangles.push_back({ring[0], ring[1], ring[2]});
            layer.triangle_tet.push_back(ti);
        } else if (ring_size == 4) {  // split along the shorter diagonal
            const auto& v = layer.vertices;
            const bool diagonal_02 = squared_distance(v[ring[0]], v[ring[2]]) <=
                                     squared_distance(v[ring[1]], v[ring[3]]);
            if (diagonal_02) {
                layer.triangles.push_back({ring[0], ring[1], ring[2]});
                layer.triangles.push_back({ring[0], ring[2], ring[3]});
            } else {
                layer.triangles.push_back({ring[0], ring[1], ring[3]});
                layer.triangles.push_back({ring[1], ring[2], ring[3]});
            }
            layer.triangle_tet.push_back(ti);
            layer.triangle_tet.push_back(ti);
        }
    }
    clean_up(layer, tolerance);
    return layer;
}

LayerMesh slice_tet_mesh(const TetMesh& mesh, double z, const SliceOptions& options) {
    return slice_tet_mesh(mesh, build_slice_index(mesh), z, options);
}

std::vector<LayerMesh> slice_layers(const TetMesh& mesh, std::span<const double> heights,
                                    const SliceOptions& options, const StepControl& control) {
    const SliceIndex index = build_slice_index(mesh);
    std::vector<LayerMesh> layers;
    layers.reserve(heights.size());
    for (std::size_t i = 0; i < heights.size(); ++i) {
        control.check_cancel();
        layers.push_back(slice_tet_mesh(mesh, index, heights[i], options));
        control.report("slice", static_cast<double>(i + 1) / static_cast<double>(heights.size()));
    }
    return layers;
}

}  // namespace fibrecell::planner
