#pragma once
// Which tets a horizontal plane can cut, found without scanning the whole mesh: the mesh's z range
// is split into buckets about one tet tall, each listing the tets whose z range overlaps it. A
// query reads one bucket, so slicing a layer costs O(tets near the plane), not O(all tets).

#include "planner/mesh/tet_mesh.hpp"

#include <span>
#include <vector>

namespace fibrecell::planner {

struct SliceIndex {
    double z_min = 0;                 // lowest vertex z [mm]
    double z_max = 0;                 // highest vertex z [mm]
    double bucket_height = 1;         // [mm]
    double size = 0;                  // bounding-box diagonal [mm], the scale of tolerances
    std::vector<int> bucket_offsets;  // #buckets + 1, into bucket_tets
    std::vector<int> bucket_tets;     // tet ids, ascending within a bucket
    std::vector<double> tet_z_min;    // #T lowest vertex z per tet [mm]
    std::vector<double> tet_z_max;    // #T highest vertex z per tet [mm]

    // Every tet whose z range [tet_z_min, tet_z_max] contains z, plus some near it; ascending.
    std::span<const int> tets_near(double z) const;
};

// Validates the mesh as it goes: throws std::invalid_argument naming the tet or vertex for a vertex
// index out of range or a non-finite vertex. Memory about 2 entries per tet.
SliceIndex build_slice_index(const TetMesh& mesh);

}  // namespace fibrecell::planner
