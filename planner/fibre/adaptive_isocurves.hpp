#pragma once
// Adaptive isocurve extraction (paper Section 4.3, Steps 1-7): as many isocurves of s as fit
// with every pair of neighbouring curves more than W apart, or, with a crowded fraction, as many
// as fit W apart over all but that fraction of the area, cut back to W where they crowd.

#include "planner/fibre/isocurves.hpp"
#include "planner/layers/layer_mesh.hpp"

#include <vector>

namespace fibrecell::planner {

struct AdaptiveIsocurveOptions {
    double spacing_mm = 1.0;  // W: neighbouring fibre paths must be further apart than this
    int max_curves = 100000;  // guard against a runaway Step 4 on a degenerate field
    // A piece whose s varies less than this is treated as carrying no tension (no curves).
    double min_range = 1e-9;
    // The fraction of the piece's area allowed to crowd: n is chosen so that neighbouring curves
    // lie at least W apart wherever |grad s| is below its (1 - crowded_fraction) area quantile,
    // and the curves are then cut back to W where they crowd (trim_to_spacing). 0: the paper's
    // Steps 3-6, where the single closest pair decides n for the whole piece.
    double crowded_fraction = 0.0;
    // Multiplies the n the crowded fraction gives (more fibre, cut back to W where it crowds):
    // how a fibre budget is met. Anything but 1 chooses n as a crowded fraction does.
    double density_scale = 1.0;
};

struct AdaptiveIsocurves {
    std::vector<Polyline> curves;  // level = isovalue index within the piece
    int count = 0;                 // n, the number of isovalues finally used
    double geodesic_span_mm = 0;   // D of Step 2
    // d of the final set (or W*2 when nothing is near); 0 with a crowded fraction (not needed).
    double min_distance_mm = 0;
    double trimmed_mm = 0;     // curve length cut back where it crowded
    int extractions = 0;       // how often Steps 3/5 ran
    int counts_ruled_out = 0;  // Step 5 counts over-dense within one triangle (not extracted)
};

// One connected piece of a layer (see split_pieces) with its scalar field s (#V).
AdaptiveIsocurves adaptive_isocurves(const LayerMesh& piece, const std::vector<double>& s,
                                     const AdaptiveIsocurveOptions& options = {});

}  // namespace fibrecell::planner
