#pragma once
// Paper Section 4.4, Step 4: fibre curve ends that are left free and lie close to another free
// end are joined by a straight link, so the fibre runs on instead of being cut and re-threaded.

#include "planner/fibre/isocurves.hpp"
#include "planner/fibre/path_chains.hpp"
#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/polygon_offset.hpp"

#include <vector>

namespace fibrecell::planner {

struct EndJoinOptions {
    double max_gap_mm = 2.0;    // join ends nearer than this (the paper: 2W)
    double clearance_mm = 1.0;  // a link keeps this far from every third curve (W)
    // Where a link may run (loops, even-odd; null: anywhere): a link across a hole or a notch
    // of the part is not made.
    const RegionClip* keep_inside = nullptr;
};

// pieces: open (or closed, ignored) curves; taken: links already made (their ends are not free);
// obstacles: other curves the links must keep clear of (e.g. boundary rings). Returns the new
// links, nearest pairs first; a piece's two ends may be joined to each other (it closes).
std::vector<Link> join_close_ends(const std::vector<Polyline>& pieces,
                                  const std::vector<Link>& taken,
                                  const std::vector<Polyline>& obstacles,
                                  const EndJoinOptions& options = {});

}  // namespace fibrecell::planner
