#pragma once
// The volume model every planner stage works on: a tetrahedral mesh, optional per-element stress,
// and named vertex groups (Gmsh physical groups, the reference data's selection flags).

#include <Eigen/Core>

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fibrecell::planner {

using Tet = std::array<int, 4>;  // 0-based vertex indices, positively oriented

struct TetMesh {
    std::vector<Eigen::Vector3d> vertices;  // #V positions [mm]
    std::vector<Tet> tets;                  // #T elements, (v1-v0)·((v2-v0)×(v3-v0)) > 0

    std::size_t vertex_count() const { return vertices.size(); }
    std::size_t tet_count() const { return tets.size(); }
};

// Signed volume of tet t [mm^3]; positive for the orientation the planner expects.
double signed_volume(const TetMesh& mesh, const Tet& t);

// Symmetric 3x3 Cauchy stress tensor [MPa].
using StressTensor = Eigen::Matrix3d;

struct VolumeModel {
    TetMesh mesh;
    std::optional<std::vector<StressTensor>> stress;        // one per tet, when the file has it
    std::map<std::string, std::vector<int>> vertex_groups;  // name -> sorted vertex indices
};

}  // namespace fibrecell::planner
