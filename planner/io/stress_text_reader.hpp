#pragma once
// Reader for per-element stress as comma-separated text (the reference FEA data's format), usable
// beside a mesh of any format.

#include "planner/mesh/tet_mesh.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::planner {

// One line per tet: `elemId,P,S11,S22,S33,S12,S13,S23`. elemId is the tet's 1-based position in
// the mesh; every id in 1..tet_count must appear exactly once, in any order (the reference files
// are in order). P, the exporter's principal value, must be a number but is ignored. The tensor is
// [[S11,S12,S13],[S12,S22,S23],[S13,S23,S33]] [MPa] -- note the S13-before-S23 order, unlike the
// VTK 6-component order. Blank lines are ignored; spaces around fields are allowed.
// Throws InputError naming the file and the line (or the missing element).
std::vector<StressTensor> read_stress_text(const std::string& path, std::size_t tet_count);

// The same for a file already in memory; `file` names it in messages.
std::vector<StressTensor> parse_stress_text(std::string_view text, const std::string& file,
                                            std::size_t tet_count);

}  // namespace fibrecell::planner
