#pragma once
// Reader for Gmsh meshes of tetrahedra (MSH 2.2 and 4.1, ASCII), with physical groups and
// optional per-element stress.

#include "planner/mesh/tet_mesh.hpp"

#include <string>
#include <string_view>

namespace fibrecell::planner {

// Reads a Gmsh MSH file, format 2.x or 4.1, ASCII (binary files are rejected with a hint).
//
// Elements: 4-node tetrahedra (type 4) become the mesh, in file order. Second-order tets and all
// other volume elements are rejected; points, lines and surface elements are not part of the mesh.
// Nodes: Gmsh node tags may be arbitrary; the mesh keeps only nodes used by tets, in file order,
// numbered from 0.
// Groups: every physical group of triangles or tets becomes a vertex group named from
// $PhysicalNames, or "physical_<tag>" when unnamed, holding the vertices of its elements that are
// in the tet mesh (groups of the same name are merged).
// Stress: an $ElementData view with 6 or 9 components (order: stress_components.hpp), the view
// named "stress" (any case) when there is one, else the only such view; it must give every tet a
// value, keyed by element tag. Other views and sections are skipped.
//
// Throws InputError naming the file and the line, or the Gmsh element/node tag, for anything
// malformed; the result has passed validate_model.
VolumeModel read_msh(const std::string& path);

// The same for a file already in memory; `file` names it in messages.
VolumeModel parse_msh(std::string_view text, const std::string& file);

}  // namespace fibrecell::planner
