#include "planner/plan/report.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace fibrecell::planner {

nlohmann::json field_stage_report(const JobSpec& job, const FieldStageResult& r) {
    using nlohmann::json;
    const auto& f = r.field;
    std::size_t by_rule[3] = {0, 0, 0};
    for (auto rule : f.rule) ++by_rule[static_cast<int>(rule)];
    const double n = static_cast<double>(std::max<std::size_t>(1, f.v_e.size()));
    const double sigma_max =
        f.sigma_e.empty() ? 0.0 : *std::max_element(f.sigma_e.begin(), f.sigma_e.end());

    const DotHistogram& dots = r.neighbour_dots;
    json dot_fractions = json::array();
    for (std::uint64_t c : dots.counts)
        dot_fractions.push_back(dots.pairs ? static_cast<double>(c) / dots.pairs : 0.0);

    json report = {
        {"format", "fibrecell.report/1"},
        {"job", job.name},
        {"stage", "field"},
        {"strategy", to_string(job.planner.strategy)},
        {"model",
         {{"file", job.model.mesh_path},
          {"tets", r.model.mesh.tet_count()},
          {"vertices", r.model.mesh.vertex_count()},
          {"stress_source", r.fea ? "fea" : "file"}}},
        {"field",
         {{"sigma_e_max_mpa", sigma_max},
          {"rule_first_principal", by_rule[0]},
          {"rule_second_principal", by_rule[1]},
          {"rule_no_tension", by_rule[2]},
          {"mst_reorientation", job.planner.mst_reorientation},
          {"incompatibility_removal", job.planner.incompatibility_removal},
          {"mst_components", r.mst.components},
          {"mst_flipped", r.mst.flipped},
          {"incompatibility_rule", to_string(job.planner.incompatibility_rule)},
          {"eta", job.planner.eta},
          {"v_undefined", r.removed},
          {"v_undefined_fraction", static_cast<double>(r.removed) / n},
          {"v_undefined_fraction_by_rule",
           {{"all", r.removed_fraction_by_rule[0]},
            {"any", r.removed_fraction_by_rule[1]},
            {"majority", r.removed_fraction_by_rule[2]}}},
          // The paper's Fig. 8, over the pairs Eq. 2 judges.
          {"neighbour_dots",
           {{"pairs", dots.pairs},
            {"bin_width", 2.0 / DotHistogram::bin_count},
            {"from", -1.0},
            {"fraction", dot_fractions},
            {"at_most_eta_fraction",
             dots.pairs ? static_cast<double>(dots.at_most_eta) / dots.pairs : 0.0}}}}},
        {"timings_s",
         {{"read", r.timings.read},
          {"fea", r.timings.fea},
          {"principal", r.timings.principal},
          {"mst_reorientation", r.timings.mst_reorientation},
          {"incompatible_removal", r.timings.incompatible_removal},
          {"total", r.timings.total}}},
    };
    if (r.fea) {
        const auto& s = *r.fea;
        report["fea"] = {
            {"unknowns", s.dof_count},
            {"solver", s.solver},
            {"max_displacement_mm", s.max_displacement_mm},
            {"applied_force_n", {s.applied_sum_n.x(), s.applied_sum_n.y(), s.applied_sum_n.z()}},
            {"reaction_force_n",
             {s.reaction_sum_n.x(), s.reaction_sum_n.y(), s.reaction_sum_n.z()}}};
    }
    return report;
}

namespace {

nlohmann::json coverage_json(const FibreCoverage& c) {
    return {{"coverage", c.coverage()},
            {"covered", c.covered_fraction()},
            {"region_mm2", c.region_mm2},
            {"fibre_m", c.fibre_mm / 1000.0}};
}

}  // namespace

void add_layer_stage_report(nlohmann::json& report, const LayerStageResult& layers) {
    using nlohmann::json;
    const LayerStageStats& s = layers.stats;
    report["stage"] = "layers";
    report["layers"] = {{"pla", s.pla_layers}, {"ccf", s.ccf_layers}};
    report["fibre"] = {
        {"length_m", s.fibre_length_mm / 1000.0},   {"paths", s.fibre_paths},
        {"boundary_paths", s.fibre_boundary_paths}, {"joins", s.fibre_joins},
        {"rings_joined", s.fibre_rings_joined},     {"rings_extended", s.fibre_rings_extended},
        {"dropped_short", s.dropped_short}, {"dropped_short_m", s.dropped_short_mm / 1000.0},
        {"min_spacing_mm", s.fibre_min_spacing_mm}, {"min_length_mm", s.fibre_min_length_mm}};
    report["fibre"]["mean_path_mm"] = s.fibre_paths > 0 ? s.fibre_length_mm / s.fibre_paths : 0.0;
    report["fibre"]["coverage"] = coverage_json(s.coverage);
    for (const auto& [index, c] : s.layer_coverage) {
        json layer = coverage_json(c);
        layer["layer"] = index;
        layer["paths"] = layers.layers.at(static_cast<std::size_t>(index)).paths.size();
        report["fibre"]["coverage"]["layers"].push_back(layer);
    }
    if (s.budget.layers > 0)
        report["fibre"]["budget"] = {{"target_m", s.budget.target_mm / 1000.0},
                                     {"layers", s.budget.layers},
                                     {"layers_met", s.budget.layers_met},
                                     {"worst_error", s.budget.worst_error}};
    if (s.budget.p_layers > 0)
        report["fibre"]["budget"]["p"] = {{"lowest", s.budget.lowest_p},
                                          {"highest", s.budget.highest_p}};
    for (const auto& [name, b] : s.boundaries)
        report["fibre"]["boundaries"][name] = {{"edge_m", b.edge_mm / 1000.0},
                                               {"coverage", b.coverage()},
                                               {"rings", b.rings},
                                               {"rings_joined", b.rings_joined},
                                               {"joins", b.joins},
                                               {"ring_length_m", b.ring_mm / 1000.0},
                                               {"ring_distance_mm",
                                                {{"p5", b.ring_distance_quantile(0.05)},
                                                 {"median", b.ring_distance_quantile(0.5)},
                                                 {"p95", b.ring_distance_quantile(0.95)}}}};
    report["pla"] = {{"length_m", s.pla_length_mm / 1000.0}};
    report["timings_s"]["layers"] = s.total_s;
    report["timings_s"]["per_layer_mean"] = {{"vector_field", s.mean_vector_field},
                                             {"scalar_field", s.mean_scalar_field},
                                             {"extraction", s.mean_extraction},
                                             {"connection", s.mean_connection}};
    report["quality"] = {{"alignment_weighted_cos", s.quality.alignment()},
                         {"density_sigma_p_correlation", s.quality.density_correlation()},
                         {"turning_deg_per_m", s.quality.turning_deg_per_m()}};
    report["warnings"] = layers.warnings;
}

void add_sweep_report(nlohmann::json& report, const ParameterSweep& sweep) {
    nlohmann::json points = nlohmann::json::array();
    for (const SweepPoint& p : sweep.points)
        points.push_back({{"value", p.value},
                          {"fibre_length_m", p.fibre_length_mm / 1000.0},
                          {"fibre_paths", p.fibre_paths},
                          {"alignment_weighted_cos", p.alignment},
                          {"density_sigma_p_correlation", p.density_correlation},
                          {"turning_deg_per_m", p.turning_deg_per_m},
                          {"min_spacing_mm", p.min_spacing_mm},
                          {"seconds", p.seconds}});
    report["sweep"] = {{"parameter", sweep.parameter}, {"points", points}};
}

namespace {

nlohmann::json response_json(const PartResponse& r) {
    return {
        {"stiffness_n_per_mm", r.stiffness_n_per_mm},
        {"displacement_mm", r.displacement_mm},
        {"matrix_von_mises_mpa", {{"peak", r.von_mises_peak_mpa}, {"p99", r.von_mises_p99_mpa}}},
        {"fibre_stress_peak_mpa", r.fibre_stress_peak_mpa}};
}

}  // namespace

void add_mechanics_report(nlohmann::json& report, const MechanicsResult& m) {
    const StiffnessPrediction& p = m.prediction;
    report["mechanics"] = {
        {"model", "smeared 1-D reinforcement (rule of mixtures along the fibre), linear tets"},
        {"fibre",
         {{"modulus_mpa", m.fibre.fibre_modulus_mpa},
          {"ribbon_fibre_fraction", m.fibre.fibre_volume_fraction},
          {"ribbon_mm", {m.fibre.ribbon_width_mm, m.fibre.ribbon_height_mm}},
          {"placed_m", m.fibre_placed_mm / 1000.0},
          {"unplaced_m", m.fibre_unplaced_mm / 1000.0},
          {"volume_mm3", m.fibre_volume_mm3},
          {"reinforced_tets", m.reinforced_tets},
          {"saturated_tets", m.saturated_tets},
          {"max_tet_fraction", m.max_fibre_fraction}}},
        {"bare", response_json(p.bare)},
        {"reinforced", response_json(p.reinforced)},
        {"stiffness_gain", p.gain()}};
    report["timings_s"]["mechanics"] = m.seconds;
}

}  // namespace fibrecell::planner
