#pragma once
// Where the printed fibre is in the model: per tet, the length of CCF path inside it and the
// length-weighted orientation of the path tangents (second and fourth order), found by locating
// the paths of each CCF layer on the layer's cross-section, whose triangles remember their tet.

#include "planner/fea/linear_elastic.hpp"
#include "planner/layers/layer_mesh.hpp"
#include "planner/layers/placement.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

struct FibreContent {
    std::vector<double> length_mm;  // #T fibre path length inside the tet [mm]
    // #T sum of L t t^T over the path pieces in the tet, t the unit tangent in the model frame
    // [mm]; over length_mm it is the orientation tensor (trace 1).
    std::vector<Eigen::Matrix3d> tangents;
    // #T sum of L m m^T, m = (tx^2, ty^2, tz^2, ty tz, tx tz, tx ty): the fourth-order orientation
    // tensor in Voigt form [mm] (what a 1-D reinforcement adds to a stiffness, see
    // reinforced_material.hpp).
    std::vector<VoigtStiffness> orientation4;
    double placed_mm = 0;    // path length located in some tet
    double unplaced_mm = 0;  // path length off every section triangle (should be ~0)
};

struct FibreContentOptions {
    double step_mm = 0.25;  // paths are cut into pieces of at most this length, each in one tet
};

// model_mesh: the part in its model frame (the FEA's); placement: how the plan placed it;
// layers and sections: the layer stage's (print order, bed frame, one section per layer). Only
// CCF layers count. Throws std::invalid_argument when layers and sections differ in number.
FibreContent fibre_content(const TetMesh& model_mesh, const Placement& placement,
                           const std::vector<ToolpathLayer>& layers,
                           const std::vector<LayerMesh>& sections,
                           const FibreContentOptions& options = {});

}  // namespace fibrecell::planner
