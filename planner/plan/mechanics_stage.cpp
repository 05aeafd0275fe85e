#include "planner/plan/mechanics_stage.hpp"

#include "planner/layers/placement.hpp"
#include "planner/mechanics/fibre_content.hpp"
#include "planner/mesh/boundary.hpp"
#include "planner/plan/fea_load_case.hpp"
#include "planner/stopwatch.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

namespace fibrecell::planner {

bool wants_mechanics(const JobSpec& job) {
    return job.analysis.enabled && job.analysis_load_case() != nullptr;
}

MechanicsResult run_mechanics_stage(const JobSpec& job, const FieldStageResult& field,
                                    const LayerStageResult& layers, const StepControl& control) {
    if (!wants_mechanics(job))
        throw std::invalid_argument("the job has no load case to predict its stiffness under");
    Stopwatch clock;
    const TetMesh& mesh = field.model.mesh;
    MechanicsResult out;
    out.fibre = {.fibre_modulus_mpa = job.analysis.fibre_modulus_mpa,
                 .fibre_volume_fraction = job.analysis.fibre_volume_fraction,
                 .ribbon_width_mm = job.process.ccf.line_width_mm,
                 .ribbon_height_mm = job.layers.ccf_layer_height_mm};

    control.report("mechanics", 0.0);
    const FibreContent content =
        fibre_content(mesh, placement_for(mesh, job.placement), layers.layers, layers.sections);
    const LoadCase lc =
        fea_load_case(job, *job.analysis_load_case(), field.model, boundary_triangles(mesh));
    const Reinforcement fibre = reinforcement(mesh, content, out.fibre, lc.material);
    out.fibre_placed_mm = content.placed_mm;
    out.fibre_unplaced_mm = content.unplaced_mm;
    out.fibre_volume_mm3 = fibre.fibre_volume_mm3;
    out.reinforced_tets = fibre.reinforced_tets;
    out.saturated_tets = fibre.saturated_tets;
    if (!fibre.fibre_fraction.empty())
        out.max_fibre_fraction =
            *std::max_element(fibre.fibre_fraction.begin(), fibre.fibre_fraction.end());
    out.locate_s = clock.elapsed();
    control.check_cancel();

    // The field stage solved the model's own load case already: that is the bare part.
    std::optional<BareSolution> bare;
    if (job.model.load_case && !field.fea_displacement.empty() && field.model.stress)
        bare = BareSolution{field.fea_displacement, *field.model.stress};
    out.prediction = predict_stiffness(mesh, lc, fibre, out.fibre.fibre_modulus_mpa, control, bare);
    out.seconds = clock.elapsed();
    spdlog::info(
        "plan.mechanics stiffness {:.1f} N/mm bare, {:.1f} N/mm with {:.2f} m of fibre "
        "({:.2f}x) in {:.3f} s",
        out.prediction.bare.stiffness_n_per_mm, out.prediction.reinforced.stiffness_n_per_mm,
        out.fibre_placed_mm / 1000, out.prediction.gain(), out.seconds);
    return out;
}

}  // namespace fibrecell::planner
