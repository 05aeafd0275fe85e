#pragma once
// Where one piece of a layer may carry fibre, measured on its true outline (paper Section 4.4,
// Steps 1-2, with the ribbon's width): the rings d = 1.5W along the selected boundary (or on
// the outline, rings_at_edge), the stress fibres kept d + W from it and W/2 from every other edge
// (the ribbon stays inside the part), and the curve d + W along which cut ends are joined.

#include "planner/fibre/isocurves.hpp"
#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/polygon_offset.hpp"

#include <vector>

namespace fibrecell::planner {

struct FibreRegionOptions {
    double spacing_mm = 1.0;          // W
    double arc_tolerance_mm = 0.002;  // round joins of the offsets
    // The rings with their ribbon's edge on the outline (W/2 from it, and the chords' allowance)
    // instead of the paper's d = 1.5W; the stress fibres then keep W from them as before.
    bool rings_at_edge = false;
};

struct FibreRegion {
    std::vector<Polygon> part;          // the outline inset W/2: where any ribbon fits
    std::vector<Polygon> stress;        // loops, even-odd: where stress-following fibre may lie
    std::vector<Polyline> rings;        // at d along the selected boundary: closed or arcs
    std::vector<Polygon> ring_loops;    // the whole loops at d the rings lie on
    std::vector<Polyline> link_curves;  // the edge of `stress` where it is d + W from it
};

// outline: the piece's loops [mm]; selected: the outline segments cut from the faces chosen for
// boundary-conformal fibre (may be empty: no rings, no link curves). Ring and link points lie
// on the offsets of the outline (to 1e-5 mm, round joins to the arc tolerance); no segment of
// them is longer than W.
FibreRegion fibre_region(const LayerOutline& outline, const std::vector<Segment2>& selected,
                         const FibreRegionOptions& options = {});

}  // namespace fibrecell::planner
