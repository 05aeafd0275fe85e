#pragma once
// The largest part a cell takes (cell YAML `part_limits`, docs/service.md "Size limits"): checked
// with the robot's reach before any planning work (daemon/print/part_fit.hpp), so that the work
// and memory a job costs are bounded by what the cell can print, not by what a file claims.

#include "config/yaml_section.hpp"

#include <array>

namespace fibrecell::daemon {

struct PartLimits {
    std::array<double, 3> max_size_mm{400, 400, 300};  // the part as placed, x y z on the bed
    int max_layers = 2000;                             // PLA layers (its height / layer height)
    // Tetrahedra of the mesh: the FEA's memory and time grow with them (docs/service.md).
    int max_tets = 300'000;
};

// Reads and checks the section (bounds, unknown keys); throws config::ConfigError naming the key.
PartLimits load_part_limits(config::Section section);

}  // namespace fibrecell::daemon
