#pragma once
// Reader for the reference FEA data set format (docs/job-format.md, "Mesh and stress files"): a
// .tet mesh with optional comma-separated stress and vertex selection files beside it.

#include "planner/mesh/tet_mesh.hpp"

#include <string>
#include <string_view>

namespace fibrecell::planner {

// `tet_path`: line 1 `N vertices`, line 2 `M tets`, N lines `x y z` [mm], M lines `4 a b c d`
// with 0-based vertex indices. `stress_path` (see stress_text_reader.hpp) and `selection_path`
// (see selection_reader.hpp; gives groups "fixed" and "handle") may be empty = absent.
// Throws InputError naming the offending file and its line, or the element (1-based, as the
// stress file numbers them); the result has passed validate_model.
VolumeModel read_tet(const std::string& tet_path, const std::string& stress_path,
                     const std::string& selection_path);

// The mesh part alone, from a file already in memory (validated); `file` names it in messages.
TetMesh parse_tet_mesh(std::string_view text, const std::string& file);

}  // namespace fibrecell::planner
