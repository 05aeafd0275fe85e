#pragma once
// Isocurves of a piecewise-linear scalar field on a layer mesh (marching triangles).

#include "planner/layers/layer_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

struct Polyline {
    std::vector<Eigen::Vector2d> points;  // [mm]
    bool closed = false;                  // the last point joins the first
    int level = 0;                        // index of the isovalue it was extracted at
};

// All isocurves s = isovalues[k] (ascending) on `layer`, with `s` per vertex. Curves end on the
// layer boundary or close on themselves; points are shared between neighbouring triangles, so a
// curve is one connected chain. A vertex whose value equals an isovalue counts as above it
// (symbolic perturbation), which keeps curves through vertices well defined.
std::vector<Polyline> extract_isocurves(const LayerMesh& layer, const std::vector<double>& s,
                                        const std::vector<double>& isovalues);

// Length of a polyline [mm], with the closing segment when closed.
double polyline_length(const Polyline& p);

}  // namespace fibrecell::planner
