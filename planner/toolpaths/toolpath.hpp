#pragma once
// Toolpaths of a plan (docs/contracts.md, toolpaths.json): per layer, the paths one head prints,
// in print order, in the bed frame (the part as placed on the bed) [mm].

#include <Eigen/Core>

#include <string_view>
#include <vector>

namespace fibrecell::planner {

// The paper's head (Section 5): its cutter sits 42 mm before the nozzle tip. The default of the
// planner's options for direct callers; a plan uses the cell's (daemon/print/print_settings.hpp).
inline constexpr double paper_cutter_distance_mm = 42;

enum class Head { pla, ccf };

enum class PathRole {
    perimeter,       // PLA outline rings
    infill,          // PLA zigzag fill
    fibre,           // CCF along the stress field (or the baseline's zigzag)
    fibre_boundary,  // CCF boundary-conformal rings
};

std::string_view to_string(Head head);
std::string_view to_string(PathRole role);

struct Toolpath {
    PathRole role = PathRole::perimeter;
    bool closed = false;                  // the last point joins the first
    std::vector<Eigen::Vector2d> points;  // in print order [mm]
};

struct ToolpathLayer {
    int index = 0;  // 0-based, in print order
    double z = 0;   // nozzle-tip height while the layer prints [mm]
    Head head = Head::pla;
    double thickness = 0;  // [mm]
    std::vector<Toolpath> paths;
};

}  // namespace fibrecell::planner
