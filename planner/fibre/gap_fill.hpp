#pragma once
// The field-dense strategy's last step on a CCF layer: where the stress paths left the fibre region
// bare (between stripes where they diverge, round the pins, beside the rings, in a piece with no
// usable field), rings from each gap's edge inwards (they follow the paths beside it) or zigzag
// lines along its mean stress or its length, whichever lays the most fibre along the stress; then
// zigzag lines in what that left. W from everything laid, W/2 inside the outline.
// The stripes carry the load; this makes the layer dense where they could not reach.

#include "planner/fibre/laid_fibre.hpp"
#include "planner/fibre/layer_field.hpp"
#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <cstddef>
#include <vector>

namespace fibrecell::planner {

struct GapFillOptions {
    double spacing_mm = 1.0;          // W
    double cutter_distance_mm = 42;   // a shorter piece cannot be laid and cut
};

struct GapFill {
    std::vector<Toolpath> paths;  // role fibre, as laid (W kept against `laid` and each other)
    std::size_t gaps = 0;         // islands of the bare region big enough for a cutter-long line
    std::size_t ringed_gaps = 0;  // of them, filled with rings from their edge inwards
};

// layer, field: the layer's mesh and its field (the gaps' directions); laid: the layer's fibre so
// far (its paths `laid_paths`), to which the fill is added. The bare region is the outline inset
// W/2 less W round every laid path.
GapFill fill_gaps(const LayerMesh& layer, const LayerField& field,
                  const std::vector<Toolpath>& laid_paths, LaidFibre& laid,
                  const GapFillOptions& options = {});

}  // namespace fibrecell::planner
