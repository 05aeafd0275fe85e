#pragma once
// Distance on a layer from chosen boundary vertices by the heat method (Crane, Weischedel and
// Wardetzky 2013): a short heat flow from the sources, its normalised gradient, and the field
// whose gradient best matches it. Needed for the boundary-conformal fibres of Section 4.4,
// Step 1, where the distance must be metric (mm) for the isocurves d = 1.5W and 2.5W.

#include "planner/layers/layer_mesh.hpp"

#include <vector>

namespace fibrecell::planner {

struct HeatDistanceOptions {
    double time_factor = 1.0;  // t = time_factor * (mean edge length)^2, as the paper recommends
};

// sources: vertex indices of `layer` (the selected boundary). Returns #V distances [mm], 0 at the
// sources; +infinity on pieces of the layer that hold no source.
std::vector<double> heat_distance(const LayerMesh& layer, const std::vector<int>& sources,
                                  const HeatDistanceOptions& options = {});

}  // namespace fibrecell::planner
