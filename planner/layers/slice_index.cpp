#include "planner/layers/slice_index.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fibrecell::planner {

namespace {

constexpr long kMaxBuckets = 1 << 20;

int bucket_of(const SliceIndex& index, double z, int bucket_count) {
    const double b = std::floor((z - index.z_min) / index.bucket_height);
    return static_cast<int>(std::clamp(b, 0.0, static_cast<double>(bucket_count - 1)));
}

}  // namespace

SliceIndex build_slice_index(const TetMesh& mesh) {
    SliceIndex index;
    const int vertex_count = static_cast<int>(mesh.vertices.size());
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    for (int v = 0; v < vertex_count; ++v) {
        const Eigen::Vector3d& p = mesh.vertices[v];
        if (!p.allFinite())
            throw std::invalid_argument("slice index: vertex " + std::to_string(v) +
                                        " is not finite");
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const std::size_t tet_count = mesh.tets.size();
    index.tet_z_min.assign(tet_count, 0.0);
    index.tet_z_max.assign(tet_count, 0.0);
    double extent_sum = 0;
    for (std::size_t t = 0; t < tet_count; ++t) {
        double z0 = INFINITY, z1 = -INFINITY;
        for (int v : mesh.tets[t]) {
            if (v < 0 || v >= vertex_count)
                throw std::invalid_argument("slice index: tet " + std::to_string(t) +
                                            " uses vertex " + std::to_string(v) + " of " +
                                            std::to_string(vertex_count));
            z0 = std::min(z0, mesh.vertices[v].z());
            z1 = std::max(z1, mesh.vertices[v].z());
        }
        index.tet_z_min[t] = z0;
        index.tet_z_max[t] = z1;
        extent_sum += z1 - z0;
    }
    if (tet_count == 0) {
        index.bucket_offsets = {0, 0};
        return index;
    }
    index.z_min = lo.z();
    index.z_max = hi.z();
    index.size = (hi - lo).norm();

    // Buckets as tall as the mean tet: each tet lands in about two.
    const double range = index.z_max - index.z_min;
    const double mean_extent = extent_sum / static_cast<double>(tet_count);
    long bucket_count = 1;
    if (range > 0 && mean_extent > 0)
        bucket_count = std::clamp(static_cast<long>(std::ceil(range / mean_extent)), 1L,
                                  std::min(kMaxBuckets, static_cast<long>(tet_count)));
    index.bucket_height = range > 0 ? range / static_cast<double>(bucket_count) : 1.0;
    const int buckets = static_cast<int>(bucket_count);

    // Counting sort into CSR; tets are visited in order, so each bucket is ascending.
    index.bucket_offsets.assign(buckets + 1, 0);
    for (std::size_t t = 0; t < tet_count; ++t) {
        const int b0 = bucket_of(index, index.tet_z_min[t], buckets);
        const int b1 = bucket_of(index, index.tet_z_max[t], buckets);
        for (int b = b0; b <= b1; ++b) ++index.bucket_offsets[b + 1];
    }
    for (int b = 0; b < buckets; ++b) index.bucket_offsets[b + 1] += index.bucket_offsets[b];
    index.bucket_tets.resize(index.bucket_offsets.back());
    std::vector<int> fill(index.bucket_offsets.begin(), index.bucket_offsets.end() - 1);
    for (std::size_t t = 0; t < tet_count; ++t) {
        const int b0 = bucket_of(index, index.tet_z_min[t], buckets);
        const int b1 = bucket_of(index, index.tet_z_max[t], buckets);
        for (int b = b0; b <= b1; ++b) index.bucket_tets[fill[b]++] = static_cast<int>(t);
    }
    return index;
}

std::span<const int> SliceIndex::tets_near(double z) const {
    const int buckets = static_cast<int>(bucket_offsets.size()) - 1;
    if (buckets <= 0 || bucket_tets.empty() || !(z >= z_min && z <= z_max)) return {};
    const int b = bucket_of(*this, z, buckets);
    return {bucket_tets.data() + bucket_offsets[b],
            static_cast<std::size_t>(bucket_offsets[b + 1] - bucket_offsets[b])};
}

}  // namespace fibrecell::planner
