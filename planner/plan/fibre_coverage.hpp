#pragma once
// How much of a CCF layer its fibre covers (report.json `fibre.coverage`): the layer's fibre
// region is its outline inset W/2, where a W-wide ribbon fits. Coverage is fibre length x W over
// the region's area (1: the region laid full at spacing W; fibre laid twice counts twice); the
// covered area is the union of the W-wide ribbons within the region, which does not reward
// overlap. Measured on the layer's true outline, the same way for every strategy.

#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <vector>

namespace fibrecell::planner {

struct FibreCoverage {
    double ribbon_mm = 0;    // W
    double region_mm2 = 0;   // the outline inset W/2
    double fibre_mm = 0;     // fibre laid in the layer
    double covered_mm2 = 0;  // the ribbons' union within the region

    double coverage() const { return region_mm2 > 0 ? fibre_mm * ribbon_mm / region_mm2 : 0.0; }
    double covered_fraction() const { return region_mm2 > 0 ? covered_mm2 / region_mm2 : 0.0; }
    // Sums over layers (a job has one W). A layer whose region vanished (narrower than W) adds
    // its fibre, if any, and no area.
    FibreCoverage& operator+=(const FibreCoverage& o);
};

// paths: the layer's fibre paths (every role) [mm]; w: the ribbon's width [mm], positive (else
// std::invalid_argument).
FibreCoverage fibre_coverage(const LayerOutline& outline, const std::vector<Toolpath>& paths,
                             double w);

}  // namespace fibrecell::planner
