#pragma once
// The second planning stage: place the part, cut it into the layer schedule and plan every
// layer's paths (PLA matrix rings + zigzag; CCF fibres by the job's strategy).

#include "planner/executor.hpp"
#include "planner/fibre/layer_field.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/layers/layer_mesh.hpp"
#include "planner/plan/boundary_fibre_stats.hpp"
#include "planner/plan/fibre_coverage.hpp"
#include "planner/plan/fibre_quality.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/progress.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <string>
#include <utility>
#include <vector>

namespace fibrecell::planner {

struct LayerStageStats {
    int pla_layers = 0, ccf_layers = 0;
    double fibre_length_mm = 0, pla_length_mm = 0;
    int fibre_paths = 0, dropped_short = 0;
    double dropped_short_mm = 0;   // the fibre those left out would have laid
    int fibre_boundary_paths = 0;  // of fibre_paths, boundary-conformal rings (Section 4.4)
    int fibre_joins = 0;           // curve ends joined by the connection (Section 4.4)
    int fibre_rings_joined = 0;    // rings shorter than the cutter laid on from a stress path
    int fibre_rings_extended = 0;  // arcs shorter than the cutter run on along their loop
    // Smallest distance between two fibre points of a layer, between paths or within one (4W
    // apart along it), capped at 3W (0: none); fibre_spacing_mm.
    double fibre_min_spacing_mm = 0;
    double fibre_min_length_mm = 0;  // shortest fibre path kept (0: none)
    // planner.fibre_budget, over the CCF layers it applied to (those with a target above 0).
    struct Budget {
        int layers = 0, layers_met = 0;  // within BudgetFit::tolerance of their target
        double target_mm = 0;            // summed over those layers
        double worst_error = 0;          // largest |laid - target| / target of a layer
        // The field strategy's contrast p over those layers (planner.p lowered to meet more).
        int p_layers = 0;
        double lowest_p = 0, highest_p = 0;
    } budget;
    // Per-CCF-layer means [s], the paper's Table 1 columns (field strategy).
    double mean_vector_field = 0, mean_scalar_field = 0, mean_extraction = 0, mean_connection = 0;
    double total_s = 0;        // all per-layer work, wall clock
    FibreQualitySums quality;  // over all CCF layers
    // Per CCF layer (its index in print order), and over all of them.
    std::vector<std::pair<int, FibreCoverage>> layer_coverage;
    FibreCoverage coverage;
    // Per boundary_fibres region, in the job's order (field strategy), over all CCF layers.
    std::vector<std::pair<std::string, BoundaryFibreStats>> boundaries;
};

struct LayerStageResult {
    std::vector<ToolpathLayer> layers;   // print order, bed frame [mm]
    std::vector<LayerOutline> outlines;  // one per layer
    std::vector<LayerMesh> sections;     // one per layer (CCF ones carry the field)
    std::vector<std::vector<double>>
        sigma;  // per layer: sigma_f per triangle (CCF field), or empty
    std::vector<std::string> warnings;
    LayerStageStats stats;
};

struct LayerStageOptions {
    // Cutter to nozzle tip on the cell that prints the job: shorter fibre paths cannot be laid
    // and are dropped (the print settings give the cell's value, daemon/print/print_settings).
    double cutter_distance_mm = paper_cutter_distance_mm;
    // Runs the independent layers; null: one after another on the calling thread.
    Executor* executor = nullptr;
};

// `control.progress` gets ("layers", fraction) from the executor's threads, never two calls at
// once.
LayerStageResult run_layer_stage(const JobSpec& job, const FieldStageResult& field,
                                 const LayerStageOptions& options = {},
                                 const StepControl& control = {});

}  // namespace fibrecell::planner
