#pragma once
// The first planning stage (paper Section 4.1): read the model, get its stress (from the file or
// the built-in FEA), and turn it into the processed 3D tensile direction field.

#include "planner/field/incompatibility.hpp"
#include "planner/field/mst_reorientation.hpp"
#include "planner/field/tensile_field.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/mesh/tet_mesh.hpp"
#include "planner/progress.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace fibrecell::planner {

// Wall-clock seconds of each step, named as in report.json's timings_s.
struct FieldStageTimings {
    double read = 0;  // set by whoever read the model
    double fea = 0;   // 0 when the stress came with the model
    double principal = 0;
    double mst_reorientation = 0;
    double incompatible_removal = 0;
    double total = 0;
};

struct FeaSummary {
    std::size_t dof_count = 0;
    std::string solver;
    double max_displacement_mm = 0;
    Eigen::Vector3d reaction_sum_n = Eigen::Vector3d::Zero();  // balances the applied loads
    Eigen::Vector3d applied_sum_n = Eigen::Vector3d::Zero();
};

struct FieldStageResult {
    VolumeModel model;                    // mesh in the model frame, stress filled in
    TensileField field;                   // v_e re-oriented by the MST
    std::vector<std::uint8_t> v_defined;  // 0 where incompatibility removal undefined v_e
    MstReorientationResult mst;           // empty when planner.mst_reorientation is off
    DotHistogram neighbour_dots;          // v_e.v_e* of neighbours, before the removal (Fig. 8)
    std::size_t removed = 0;              // elements with v_e undefined (0 when the removal is off)
    // The fraction each reading of Eq. 2 would undefine, indexed by IncompatibilityRule, so the
    // report can compare them on every part.
    std::array<double, 3> removed_fraction_by_rule = {0, 0, 0};
    std::optional<FeaSummary> fea;
    // #V the FEA's displacement [mm] (empty when the stress came with the model): the bare part
    // the mechanics stage compares the reinforced one with.
    std::vector<Eigen::Vector3d> fea_displacement;
    FieldStageTimings timings;
};

// Runs the stage for `job` on its model (planner/io/read_model.hpp reads it; its stress may be
// missing when the job has a load case). timings.read stays 0: the reading is the caller's.
// Throws FeaError (load case), std::invalid_argument (no stress and no load case, regions that do
// not fit the mesh) and Cancelled.
FieldStageResult run_field_stage(const JobSpec& job, VolumeModel model,
                                 const StepControl& control = {});

}  // namespace fibrecell::planner
