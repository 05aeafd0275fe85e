#pragma once
// Boundary-conformal fibres (paper Section 4.4, Steps 1-3): rings at d = 1.5W from the chosen
// boundary, the stress-following curves cut back to d = 2.5W (and to W/2 from every other edge),
// and their new ends joined in pairs along the curve d = 2.5W, which itself is not printed.

#include "planner/fibre/fibre_region.hpp"
#include "planner/fibre/isocurves.hpp"
#include "planner/fibre/path_chains.hpp"

#include <vector>

namespace fibrecell::planner {

struct BoundaryConformalOptions {
    double spacing_mm = 1.0;  // W
    double max_link_mm = 0;   // longest join along the link curve; 0 = 6 W
};

struct BoundaryConformal {
    std::vector<Polyline> boundary;  // the d = 1.5W rings (role fibre-boundary)
    std::vector<Polyline> pieces;    // the stress curves' runs inside region.stress
    std::vector<Link> links;         // Step 3: cut ends joined along the link curve
};

// region: where the piece's fibre may lie (fibre_region); stress: the curves C_str of the piece.
// A stress curve wholly outside the stress region disappears; a closed one that leaves it opens.
BoundaryConformal conform_to_boundary(const FibreRegion& region,
                                      const std::vector<Polyline>& stress,
                                      const BoundaryConformalOptions& options = {});

}  // namespace fibrecell::planner
