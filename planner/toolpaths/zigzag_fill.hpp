#pragma once
// Zigzag (boustrophedon) fill of a region: parallel scan lines clipped to the region, neighbouring
// scan segments joined along the region boundary into long open paths. Shared by the PLA infill
// and the baseline fibre fill.

#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <vector>

namespace fibrecell::planner {

struct ZigzagOptions {
    double spacing_mm = 0.8;       // distance between neighbouring scan lines
    double angle_deg = 0;          // scan-line direction, counter-clockwise from +x
    double max_link_spacings = 4;  // longest boundary link joining two scan segments [spacings]
};

// `region` [mm]: loops read even-odd (outer loops and holes, any orientation); the scan lines are
// centrelines, so pass the region already inset by half a line width. Lines run at `angle_deg`,
// `spacing_mm` apart, centred across the region's extent so that none touches its extreme edge.
// A scan segment's end is linked to the next line's segment end when the boundary between them
// stays between the two lines and is at most max_link_spacings * spacing_mm long; the link
// follows the boundary, so every point stays in the closed region. Returns open paths of `role`
// in scan order (lowest line first). Throws std::invalid_argument on a non-positive spacing.
std::vector<Toolpath> zigzag_fill(const std::vector<Polygon>& region, PathRole role,
                                  const ZigzagOptions& options = {});

}  // namespace fibrecell::planner
