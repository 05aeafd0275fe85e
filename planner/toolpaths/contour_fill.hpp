#pragma once
// Rings that follow the outline plus a zigzag over what the rings leave: the pattern of both the
// PLA matrix layers (perimeters + infill) and the baseline fibre strategy (boundary rings + fibre
// zigzag). One implementation, parameterised by pitch and roles.

#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <vector>

namespace fibrecell::planner {

struct ContourFillOptions {
    double pitch_mm = 0.8;                     // line width: ring pitch and zigzag spacing
    int rings = 2;                             // rings per island before the zigzag
    double angle_deg = 0;                      // zigzag direction, counter-clockwise from +x
    PathRole ring_role = PathRole::perimeter;  // role of the closed rings
    PathRole fill_role = PathRole::infill;     // role of the open zigzag paths
    double max_link_spacings = 4;              // see ZigzagOptions
    double arc_tolerance_mm = 0.002;           // see OffsetOptions
    Eigen::Vector2d start_mm{0, 0};            // nozzle before the layer: ordering starts here
};

// The inset [mm] of the zigzag region from the outline: the centreline of ring i lies at
// pitch/2 + i*pitch, and the zigzag centrelines stay pitch/2 further in (max(rings, 1/2) *
// pitch). So the zigzag's boundary links run exactly one line width from the innermost ring,
// bead beside bead, while the rounded ends of the scan lines reach up to half a width into that
// ring's bead, which bonds the fill to it.
double contour_fill_inset_mm(const ContourFillOptions& options);

// `outline` [mm]: outer loops and holes (read even-odd). Per island: ring i (0-based) is the
// outline offset inwards by pitch/2 + i*pitch (outer loops shrink, holes grow; a ring that
// vanishes ends the rings), then a zigzag at `pitch_mm` spacing over the outline inset by
// contour_fill_inset_mm. Islands in nearest-first order from start_mm; within an island the rings
// first, then the zigzag, each nearest-first. Throws std::invalid_argument on a non-positive
// pitch, a negative ring count or a bad outline loop.
std::vector<Toolpath> contour_fill(const LayerOutline& outline, const ContourFillOptions& options);

}  // namespace fibrecell::planner
