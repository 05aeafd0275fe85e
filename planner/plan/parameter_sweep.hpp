#pragma once
// A layer-stage parameter planned at several values over one field stage (the paper's Fig. 9:
// the fibre length the density exponent p lays). `fibrecell plan --sweep p=0,0.5,1,2` writes the
// points into report.json's `sweep` and plots them in the preview.
//
//   ParameterSweep sweep = parse_sweep("p=0,0.5,1,2");
//   run_sweep(sweep, job, field, {.cutter_distance_mm = 42});

#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/progress.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::planner {

// What one value gave, from the layer stage's own statistics.
struct SweepPoint {
    double value = 0;
    double fibre_length_mm = 0;
    int fibre_paths = 0;
    double alignment = 0, density_correlation = 0, turning_deg_per_m = 0;
    double min_spacing_mm = 0;
    double seconds = 0;  // the layer stage's wall clock
};

struct ParameterSweep {
    // A planner.* key the layer stage reads (the field stage runs once): p,
    // sigma_cap_percentile, crowded_fraction.
    std::string parameter;
    std::vector<double> values;
    std::vector<SweepPoint> points;  // one per value, once run
};

// "NAME=V1,V2,...": throws std::invalid_argument naming the bad part (an unknown name, a value
// that is not a number or out of the job file's range, no values, more than 16).
ParameterSweep parse_sweep(std::string_view text);

// Plans the layers once per value of `sweep` (the job's other settings as they are) and fills
// sweep.points. Progress goes out as ("sweep", fraction); throws Cancelled.
void run_sweep(ParameterSweep& sweep, const JobSpec& job, const FieldStageResult& field,
               LayerStageOptions options = {}, const StepControl& control = {});

}  // namespace fibrecell::planner
