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
    double fill_spacing_mm = 0;                // zigzag spacing when wider (0: the pitch)
    int rings = 2;                             // rings per island before the zigzag
    double angle_deg = 0;                      // zigzag direction, counter-clockwise from +x
    PathRole ring_role = PathRole::perimeter;  // role of the closed rings
    PathRole fill_role = PathRole::infill;     // role of the open zigzag paths
    // PLA (true): the zigzag's scan lines reach half a width into the innermost ring's bead,
    // which bonds the fill to the perimeter. Fibre (false): ribbons never overlap nor leave the
    // part: the zigzag keeps a whole pitch from the innermost ring, and every inset is widened by
    // the round joins' chord error (up to 2.25 arc tolerances inside the arc, see offset_region).
    bool ribbons_overlap = true;
    double max_link_spacings = 4;     // see ZigzagOptions
    double arc_tolerance_mm = 0.002;  // see OffsetOptions
    Eigen::Vector2d start_mm{0, 0};   // nozzle before the layer: ordering starts here
};

// The inset [mm] of ring i (0-based) from the outline: pitch/2 + i*pitch (plus the chord margin
// unless ribbons_overlap).
double contour_ring_inset_mm(int ring, const ContourFillOptions& options);

// The inset [mm] of the zigzag region from the outline. With ribbons_overlap the zigzag
// centrelines start half a pitch inside the innermost ring (max(rings, 1/2) * pitch): its
// boundary links and scan-line ends lie half a width from the ring's centreline, their bead over
// half of the ring's. Without, a whole pitch inside it (rings*pitch + pitch/2 plus the ring's
// chord margin and its own): no zigzag point nearer than one pitch to any ring, by the triangle
// inequality on distances to the outline.
double contour_fill_inset_mm(const ContourFillOptions& options);

// `outline` [mm]: outer loops and holes (read even-odd). Per island: ring i (0-based) is the
// outline offset inwards by contour_ring_inset_mm (outer loops shrink, holes grow; a ring that
// vanishes ends the rings), then a zigzag at `pitch_mm` spacing over the outline inset by
// contour_fill_inset_mm. Islands in nearest-first order from start_mm; within an island the rings
// first, then the zigzag, each nearest-first. Throws std::invalid_argument on a non-positive
// pitch, a negative ring count or a bad outline loop.
std::vector<Toolpath> contour_fill(const LayerOutline& outline, const ContourFillOptions& options);

}  // namespace fibrecell::planner
