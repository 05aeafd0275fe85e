#include "planner/plan/field_stage.hpp"

#include "planner/fea/linear_elastic.hpp"
#include "planner/field/incompatibility.hpp"
#include "planner/mesh/adjacency.hpp"
#include "planner/mesh/boundary.hpp"
#include "planner/plan/fea_load_case.hpp"
#include "planner/stopwatch.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

FeaSummary summarise(const FeaResult& r, const LoadCase& lc) {
    FeaSummary s;
    s.dof_count = r.dof_count;
    s.solver = r.solver;
    for (const auto& d : r.displacement)
        s.max_displacement_mm = std::max(s.max_displacement_mm, d.norm());
    for (const auto& f : r.reaction) s.reaction_sum_n += f;
    for (const auto& l : lc.loads) s.applied_sum_n += l.total_force_n;
    return s;
}

}  // namespace

FieldStageResult run_field_stage(const JobSpec& job, VolumeModel model,
                                 const StepControl& control) {
    FieldStageResult out;
    Stopwatch clock;
    out.model = std::move(model);

    const FaceNeighbours faces = face_neighbours(out.model.mesh);
    if (job.model.load_case) {
        control.report("fea", 0.0);
        const LoadCase lc = fea_load_case(job, *job.model.load_case, out.model,
                                          boundary_triangles(out.model.mesh, faces));
        FeaResult fea = solve_linear_elastic(out.model.mesh, lc, {}, control);
        out.model.stress = std::move(fea.stress);
        out.fea_displacement = std::move(fea.displacement);
        out.fea = summarise(fea, lc);
        out.timings.fea = clock.lap();
        spdlog::info("plan.fea {} unknowns solved with {} in {:.3f} s", fea.dof_count, fea.solver,
                     out.timings.fea);
    } else if (!out.model.stress) {
        throw std::invalid_argument(job.model.mesh_path +
                                    ": the model carries no stress field and the job gives neither "
                                    "model.stress nor model.load_case");
    }
    control.check_cancel();

    control.report("principal", 0.0);
    out.field = tensile_field(*out.model.stress, {job.planner.mu});
    out.timings.principal = clock.lap();

    if (job.planner.mst_reorientation)
        out.mst = mst_reorient(out.field.v_e, out.field.sigma_e, faces, control);
    out.timings.mst_reorientation = clock.lap();

    control.report("incompatible_removal", 0.0);
    const CsrGraph around = vertex_sharing_neighbours(out.model.mesh);
    const NeighbourAgreement agreement =
        neighbour_agreement(out.field.v_e, around, job.planner.eta);
    out.neighbour_dots = agreement.dots;
    // Off, every direction stays (the ablation); the counts still fill the report.
    out.v_defined = job.planner.incompatibility_removal
                        ? compatible_directions(agreement, job.planner.incompatibility_rule)
                        : std::vector<std::uint8_t>(out.field.v_e.size(), 1);
    out.removed =
        static_cast<std::size_t>(std::count(out.v_defined.begin(), out.v_defined.end(), 0));
    // Every reading of Eq. 2 from the same counts, for the report.
    for (auto rule : {IncompatibilityRule::all_neighbours, IncompatibilityRule::majority,
                      IncompatibilityRule::any_neighbour})
        out.removed_fraction_by_rule[static_cast<int>(rule)] = removed_fraction(agreement, rule);
    out.timings.incompatible_removal = clock.lap();

    out.timings.total = clock.elapsed();
    spdlog::info(
        "plan.field mst {:.3f} s ({} components, {} flipped{}), removal {:.3f} s "
        "({} of {} undefined, rule {}{})",
        out.timings.mst_reorientation, out.mst.components, out.mst.flipped,
        job.planner.mst_reorientation ? "" : "; off", out.timings.incompatible_removal, out.removed,
        out.v_defined.size(), to_string(job.planner.incompatibility_rule),
        job.planner.incompatibility_removal ? "" : "; off");
    return out;
}

}  // namespace fibrecell::planner
