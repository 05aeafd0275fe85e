#pragma once
// Boundary-conformal fibres (paper Section 4.4, Steps 1-3): rings at d = 1.5W from the chosen
// boundary, the stress-following curves cut back to d = 2.5W, and their new ends joined in
// pairs along the curve d = 2.5W, which itself is not printed.

#include "planner/fibre/isocurves.hpp"
#include "planner/fibre/path_chains.hpp"
#include "planner/layers/layer_mesh.hpp"

#include <vector>

namespace fibrecell::planner {

struct BoundaryConformalOptions {
    double spacing_mm = 1.0;  // W
    double max_link_mm = 0;   // longest join along the link curve; 0 = 6 W
};

struct BoundaryConformal {
    std::vector<Polyline> boundary;  // the d = 1.5W rings (role fibre-boundary)
    std::vector<Polyline> pieces;    // the stress curves without their parts where d < link level
    std::vector<Link> links;         // Step 3: cut ends joined along the link curve
    double link_level_mm = 0;        // 2.5W, raised where the heat distance is not quite metric
};

// d: #V distance [mm] from the chosen boundary on `layer` (infinite where unreachable);
// stress: the curves C_str of the layer. A stress curve that lies wholly within the link level
// disappears; a closed one that crosses it opens.
BoundaryConformal conform_to_boundary(const LayerMesh& layer, const std::vector<double>& d,
                                      const std::vector<Polyline>& stress,
                                      const BoundaryConformalOptions& options = {});

}  // namespace fibrecell::planner
