#pragma once
// Isocurves cut back where they crowd: where the field converges (a pin, a clamp, a re-entrant
// corner) neighbouring isocurves run closer than W over a short stretch while the rest of the
// layer is far sparser. Cutting those stretches keeps W there without thinning the whole layer.

#include "planner/fibre/isocurves.hpp"

#include <vector>

namespace fibrecell::planner {

struct SpacingTrimOptions {
    double spacing_mm = 1.0;    // W
    double min_piece_mm = 2.0;  // a kept piece shorter than this is dropped
};

// `curves` of levels 0..n-1. Levels are taken coarse to fine (bit-reversed order: 0, n/2, n/4,
// 3n/4, ...), so the curves kept first spread evenly over the layer and the finest levels give
// way where the field crowds them; each is laid as LaidFibre::lay does, W from those before it.
// Returns the kept pieces (resampled every W/4) with their levels, coarse to fine.
std::vector<Polyline> trim_to_spacing(const std::vector<Polyline>& curves, int n,
                                      const SpacingTrimOptions& options = {});

}  // namespace fibrecell::planner
