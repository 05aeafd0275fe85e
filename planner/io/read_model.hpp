#pragma once
// One entry point for every mesh format the planner reads, chosen by file extension.

#include "planner/mesh/tet_mesh.hpp"

#include <string>

namespace fibrecell::planner {

// Reads `mesh_path` by its extension (any case): .vtk (read_vtk), .msh (read_msh), .tet
// (read_tet, with `<stem>_selection.txt` beside it read too when it exists). Any other extension
// is an InputError.
// `stress_path`, when not empty, is a stress text file (read_stress_text) that gives the stress
// and replaces any stress the mesh file carries (which must still be well-formed). For .tet this
// is the only source of stress.
VolumeModel read_volume_model(const std::string& mesh_path, const std::string& stress_path = "");

}  // namespace fibrecell::planner
