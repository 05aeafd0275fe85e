#pragma once
// The checks every reader runs before it hands out a model: a model that passes is safe for the
// planner (finite, non-degenerate, consistently and positively oriented tets, one finite symmetric
// stress tensor per tet, vertex groups in range). Every failure throws InputError naming the file
// and the element or vertex.

#include "planner/mesh/tet_mesh.hpp"

#include <optional>
#include <string>
#include <vector>

namespace fibrecell::planner {

// How messages name elements and vertices: in the numbering the file itself uses, so a user can
// find them (Gmsh tags, VTK 0-based ids, 1-based positions for the reference .tet format).
struct FileNumbering {
    std::string element = "element";         // "element 12"
    std::string vertex = "vertex";           // "vertex 7"
    long long first = 1;                     // number of the first element/vertex by default
    std::vector<long long> element_numbers;  // per tet when not first + position (empty = default)
    std::vector<long long> vertex_numbers;   // per vertex when not first + position

    std::string element_name(std::size_t tet) const;
    std::string vertex_name(std::size_t vertex) const;
};

// A tet whose |volume| is below this fraction of its longest edge cubed is degenerate (a regular
// tet has 0.118).
constexpr double kDegenerateVolumeRatio = 1e-9;
// 9-component stress whose |s_ij - s_ji| exceeds this fraction of the tensor's largest component
// is rejected as not a stress; smaller asymmetry (round-off in exporters) is averaged away.
constexpr double kAsymmetryTolerance = 1e-3;

// All checks below with one file name; elements and vertices counted from 1.
void validate_model(VolumeModel& model, const std::string& file);
void validate_model(VolumeModel& model, const std::string& file, const FileNumbering& numbering);

// Mesh: not empty, finite coordinates, indices in range and distinct within a tet, no degenerate
// tets, consistent orientation. A mesh whose tets are all negatively oriented is flipped to
// positive (third and fourth vertex swapped); a mix of orientations is rejected.
void validate_mesh(TetMesh& mesh, const std::string& file, const FileNumbering& numbering = {});

// Stress, when present: one tensor per tet, finite, symmetric within kAsymmetryTolerance
// (then made exactly symmetric).
void validate_stress(VolumeModel& model, const std::string& file,
                     const FileNumbering& numbering = {});

// Vertex groups: indices in range; sorts them and removes duplicates.
void validate_groups(VolumeModel& model, const std::string& file);

// Why `t` is not a valid tet of a mesh with `vertex_count` vertices (index out of range or used
// twice), or nullopt. Readers call it too, to report the line.
std::optional<std::string> tet_index_problem(const Tet& t, std::size_t vertex_count);

}  // namespace fibrecell::planner
