#include "planner/plan/layer_stage.hpp"

#include "planner/plan/boundary_fibre_stats.hpp"
#include "planner/plan/fibre_budget.hpp"

#include "planner/fibre/curve_spacing.hpp"

#include "planner/fibre/boundary_sources.hpp"
#include "planner/fibre/fibre_layer.hpp"
#include "planner/layers/layer_schedule.hpp"
#include "planner/layers/outline.hpp"
#include "planner/layers/placement.hpp"
#include "planner/layers/slice.hpp"
#include "planner/mesh/region.hpp"
#include "planner/stopwatch.hpp"
#include "planner/toolpaths/contour_zigzag.hpp"
#include "planner/toolpaths/path_order.hpp"
#include "planner/toolpaths/pla_paths.hpp"

#include <algorithm>
#include <iterator>
#include <mutex>
#include <optional>

namespace fibrecell::planner {
namespace {

struct LayerWork {
    ToolpathLayer layer;
    std::vector<double> sigma;
    std::vector<std::string> warnings;
    int dropped_short = 0;
    double dropped_short_mm = 0;
    int joins = 0;
    int rings_joined = 0;
    int rings_extended = 0;
    double min_spacing = 0;
    FibreLayerTimings timings;
    FibreQualitySums quality;
    FibreCoverage coverage;
    std::vector<BoundaryFibreStats> boundaries;  // per boundary_fibres region
    std::optional<BudgetFit> budget;             // when planner.fibre_budget applied to the layer
    std::optional<double> budget_p;              // the contrast p the field strategy met it at
};

double fibre_length(const std::vector<Toolpath>& paths) {
    double mm = 0;
    for (const Toolpath& p : paths) mm += path_length(p);
    return mm;
}

// The field strategy's settings at a fibre budget's density knob (1: the job's own). Below 1 it
// lays fewer isocurves at the job's contrast p. From 1 to 2 it lowers p to 0, as the paper
// adjusted its parameters to compare strategies at the same fibre: the low-stress areas fill in
// while the fibre stays densest where sigma is highest and runs unbroken. Beyond 2 (p = 0) it lays
// more isocurves, cut back to W where they crowd (short pieces are lost to the cutter).
struct FieldDensity {
    double p;
    double density_scale;
};
FieldDensity field_density(double knob, double job_p) {
    if (knob <= 1) return {job_p, knob};
    if (knob <= 2) return {job_p * (2 - knob), 1};
    return {0, knob / 2};
}
constexpr double field_knob_max = 32;  // p = 0 and 16 times the isocurves

// The fibre [mm] planner.fibre_budget asks of CCF layer `i` (0: no budget, or nothing to meet).
double budget_target_mm(const FibreBudget& budget, const LayerOutline& outline, int ccf_ordinal,
                        const ContourZigzagOptions& baseline) {
    switch (budget.kind) {
        case FibreBudget::Kind::none:
            return 0;
        case FibreBudget::Kind::metres_per_layer:
            return budget.metres_per_layer * 1000.0;
        case FibreBudget::Kind::baseline:
            return fibre_length(contour_zigzag_paths(outline, ccf_ordinal, baseline).paths);
    }
    return 0;
}

// The part's boundary faces in each of the job's boundary_fibres regions, on the bed (in the
// job's order).
std::vector<SelectedFaces> boundary_fibre_selection(const JobSpec& job, const VolumeModel& model,
                                                    const TetMesh& placed) {
    std::vector<SelectedFaces> out;
    if (job.boundary_fibre_regions.empty() || job.planner.strategy == Strategy::contour_zigzag)
        return out;
    const std::vector<BoundaryTriangle> boundary = boundary_triangles(model.mesh);
    for (const std::string& name : job.boundary_fibre_regions) {
        std::vector<BoundaryTriangle> t = select_triangles(model, boundary, *job.find_region(name));
        if (t.empty())
            throw std::invalid_argument("region '" + name +
                                        "' (boundary_fibres) selects no boundary triangle of the "
                                        "mesh");
        out.push_back(selected_faces(placed, t));
    }
    return out;
}

// The outline edges of any of the regions (each list ascending, as selected_outline_edges gives
// them): what one selection of all their faces would give.
std::vector<std::array<int, 2>> edges_of_any(
    const std::vector<std::vector<std::array<int, 2>>>& by_region) {
    std::vector<std::array<int, 2>> all;
    for (const auto& edges : by_region) {
        std::vector<std::array<int, 2>> merged;
        std::set_union(all.begin(), all.end(), edges.begin(), edges.end(),
                       std::back_inserter(merged));
        all = std::move(merged);
    }
    return all;
}

}  // namespace

LayerStageResult run_layer_stage(const JobSpec& job, const FieldStageResult& field,
                                 const LayerStageOptions& options, const StepControl& control) {
    Stopwatch clock;
    LayerStageResult out;
    const Placement placement = placement_for(field.model.mesh, job.placement);
    const TetMesh placed = place_mesh(field.model.mesh, placement);
    const std::vector<Eigen::Vector3d> v_placed = rotate_vectors(field.field.v_e, placement);
    const std::vector<ScheduledLayer> schedule = layer_schedule(part_height(placed), job.layers);

    std::vector<double> heights;
    std::vector<int>
        ccf_ordinal;  // 0-based count among CCF layers: the baseline turns per CCF layer
    int ccf_count = 0;
    for (const auto& s : schedule) {
        heights.push_back(s.slice_z);
        ccf_ordinal.push_back(s.head == Head::ccf ? ccf_count++ : -1);
    }
    out.sections = slice_layers(placed, heights, {}, control);
    out.outlines.resize(schedule.size());

    const PlaPathOptions pla = pla_path_options(job.process);
    const ContourZigzagOptions baseline =
        contour_zigzag_options(job.planner, options.cutter_distance_mm);
    FibreLayerOptions fibre;
    fibre.field = {.smoothing_iterations = job.planner.smoothing_iterations,
                   .p = job.planner.p,
                   .sigma_cap_percentile = job.planner.sigma_cap_percentile};
    fibre.spacing_mm = job.planner.fibre_spacing_mm;
    fibre.crowded_fraction = job.planner.crowded_fraction;
    fibre.cutter_distance_mm = options.cutter_distance_mm;
    fibre.stripes = job.planner.strategy == Strategy::field_dense;
    fibre.rings_at_edge = fibre.stripes;  // dense: no bare W/2 strip along each ringed edge
    fibre.measure_spacing = false;        // measured once, on the paths a layer keeps
    const std::vector<SelectedFaces> boundary_fibre_faces =
        boundary_fibre_selection(job, field.model, placed);

    std::vector<LayerWork> work(schedule.size());
    std::mutex progress_mutex;  // the sink is called by one task at a time
    std::size_t finished = 0;
    const auto plan_layer = [&](std::size_t i) {
        const CancelScope scope(control.cancel);  // for the loops inside a layer's work
        cancellation_point();
        const ScheduledLayer& s = schedule[i];
        LayerWork& w = work[i];
        w.layer = {s.index, s.z, s.head, s.thickness, {}};
        out.outlines[i] = layer_outline(out.sections[i]);
        if (s.head == Head::pla) {
            // pla_number is 1-based; the infill angle counts PLA layers from 0.
            w.layer.paths = pla_layer_paths(out.outlines[i], s.pla_number - 1, pla);
        } else if (job.planner.strategy == Strategy::contour_zigzag) {
            // A budget of metres thins the zigzag (its density: W over its spacing); the
            // baseline's own budget is what it lays.
            const auto zigzag_at = [&](double density) {
                ContourZigzagOptions o = baseline;
                o.zigzag_spacing_mm = o.fibre_spacing_mm / density;
                return contour_zigzag_paths(out.outlines[i], ccf_ordinal[i], o);
            };
            FibreLayerPaths r;
            if (job.planner.fibre_budget.kind == FibreBudget::Kind::metres_per_layer) {
                w.budget.emplace();
                r = fit_budget(
                    zigzag_at, [](const FibreLayerPaths& p) { return fibre_length(p.paths); },
                    job.planner.fibre_budget.metres_per_layer * 1000.0, 1.0 / 32, 1.0, 1.0,
                    *w.budget, KnobShape::proportional);
            } else {
                r = zigzag_at(1.0);
            }
            w.layer.paths = std::move(r.paths);
            w.dropped_short = r.dropped_short;
            w.dropped_short_mm = r.dropped_short_mm;
        } else {
            std::vector<std::vector<std::array<int, 2>>> region_edges;
            for (const SelectedFaces& faces : boundary_fibre_faces)
                region_edges.push_back(selected_outline_edges(out.sections[i], faces));
            const auto edges = edges_of_any(region_edges);
            // The field strategy's knob is its density (field_density); the stripes' is the
            // fraction of W/period: below 1 they lie further apart.
            const double target = budget_target_mm(job.planner.fibre_budget, out.outlines[i],
                                                   ccf_ordinal[i], baseline);
            const auto fibre_at = [&](double knob) {
                FibreLayerOptions o = fibre;
                if (fibre.stripes) {
                    if (knob < 1) o.stripe_period_mm = fibre.spacing_mm / knob;
                    // A budget thins the stripes; filling what they leave would undo it.
                    o.gap_fill = target <= 0;
                } else {
                    const FieldDensity d = field_density(knob, job.planner.p);
                    o.field.p = d.p;
                    o.density_scale = d.density_scale;
                }
                return plan_fibre_layer(out.sections[i], v_placed, field.field.sigma_e,
                                        field.v_defined, edges, o);
            };
            FibreLayer r;
            if (target > 0) {
                w.budget.emplace();
                const auto length = [](const FibreLayer& l) { return fibre_length(l.paths); };
                // The contrast first (the fibre need not rise steadily with the knob past 2:
                // curves cut where they crowd can lose more to the cutter than they add).
                r = fit_budget(fibre_at, length, target, 1.0 / 16, fibre.stripes ? 1.0 : 2.0,
                               1.0, *w.budget);
                if (!fibre.stripes && !w.budget->met() && w.budget->laid_mm < target) {
                    BudgetFit more;
                    FibreLayer denser =
                        fit_budget(fibre_at, length, target, 2.0, field_knob_max, 2.0, more);
                    more.tries += w.budget->tries;
                    if (std::abs(more.laid_mm - target) < std::abs(w.budget->laid_mm - target)) {
                        r = std::move(denser);
                        *w.budget = more;
                    } else {
                        w.budget->tries = more.tries;
                    }
                }
                if (!fibre.stripes) w.budget_p = field_density(w.budget->knob, job.planner.p).p;
            } else {
                r = fibre_at(1.0);
            }
            w.layer.paths = std::move(r.paths);
            const FibreJoins joins{r.join_points, r.joined_ring_points};
            w.dropped_short = static_cast<int>(r.dropped_short);
            w.dropped_short_mm = r.dropped_short_mm;
            w.joins = static_cast<int>(r.joins);
            w.rings_joined = static_cast<int>(r.rings_joined);
            w.rings_extended = static_cast<int>(r.rings_extended);
            w.sigma = std::move(r.field.sigma_f);
            w.warnings = std::move(r.warnings);
            w.timings = r.timings;
            for (const auto& edges_of_region : region_edges)
                w.boundaries.push_back(boundary_fibre_stats(out.sections[i], edges_of_region,
                                                            w.layer.paths, fibre.spacing_mm, joins));
        }
        if (s.head == Head::ccf) {
            w.min_spacing = fibre_spacing_mm(w.layer.paths, fibre.spacing_mm);
            w.coverage = fibre_coverage(out.outlines[i], w.layer.paths, fibre.spacing_mm);
            w.quality = fibre_quality(out.sections[i], w.layer.paths, v_placed, field.field.sigma_e,
                                      field.v_defined, {.p = job.planner.p});
        }
        std::lock_guard lock(progress_mutex);
        control.report("layers", static_cast<double>(++finished) / schedule.size());
    };
    SerialExecutor serial;
    (options.executor ? *options.executor : serial).for_each(schedule.size(), plan_layer);

    LayerStageStats& st = out.stats;
    for (std::size_t b = 0; b < boundary_fibre_faces.size(); ++b)
        st.boundaries.emplace_back(job.boundary_fibre_regions[b], BoundaryFibreStats{});
    double min_length = 0;
    for (LayerWork& w : work) {
        const bool ccf = w.layer.head == Head::ccf;
        (ccf ? st.ccf_layers : st.pla_layers) += 1;
        for (const Toolpath& p : w.layer.paths) {
            const double len = path_length(p);
            if (!ccf) {
                st.pla_length_mm += len;
                continue;
            }
            st.fibre_length_mm += len;
            ++st.fibre_paths;
            st.fibre_boundary_paths += p.role == PathRole::fibre_boundary;
            min_length = min_length == 0 ? len : std::min(min_length, len);
        }
        st.dropped_short += w.dropped_short;
        st.dropped_short_mm += w.dropped_short_mm;
        if (w.budget && w.budget->target_mm > 0) {
            const BudgetFit& fit = *w.budget;
            ++st.budget.layers;
            st.budget.layers_met += fit.met();
            st.budget.target_mm += fit.target_mm;
            const double error = std::abs(fit.laid_mm - fit.target_mm) / fit.target_mm;
            st.budget.worst_error = std::max(st.budget.worst_error, error);
            if (w.budget_p) {
                const bool first = st.budget.p_layers++ == 0;
                const double p = *w.budget_p;
                st.budget.lowest_p = first ? p : std::min(st.budget.lowest_p, p);
                st.budget.highest_p = first ? p : std::max(st.budget.highest_p, p);
            }
            if (!fit.met())
                out.warnings.push_back(
                    "layer at z = " + std::to_string(w.layer.z) + ": fibre budget " +
                    std::to_string(fit.target_mm / 1000.0) + " m not met, " +
                    std::to_string(fit.laid_mm / 1000.0) + " m laid (" +
                    (fit.laid_mm < fit.target_mm ? "the layer holds no more fibre W apart"
                                                 : "the strategy lays no less here") +
                    ")");
        }
        st.fibre_joins += w.joins;
        st.fibre_rings_joined += w.rings_joined;
        st.fibre_rings_extended += w.rings_extended;
        if (w.min_spacing > 0)
            st.fibre_min_spacing_mm = st.fibre_min_spacing_mm == 0
                                          ? w.min_spacing
                                          : std::min(st.fibre_min_spacing_mm, w.min_spacing);
        st.mean_vector_field += w.timings.vector_field;
        st.mean_scalar_field += w.timings.scalar_field;
        st.mean_extraction += w.timings.extraction;
        st.mean_connection += w.timings.connection;
        st.quality += w.quality;
        if (ccf) {
            st.layer_coverage.emplace_back(w.layer.index, w.coverage);
            st.coverage += w.coverage;
        }
        for (std::size_t b = 0; b < w.boundaries.size(); ++b)
            st.boundaries[b].second += w.boundaries[b];
        out.layers.push_back(std::move(w.layer));
        out.sigma.push_back(std::move(w.sigma));
        out.warnings.insert(out.warnings.end(), w.warnings.begin(), w.warnings.end());
    }
    st.fibre_min_length_mm = min_length;
    if (st.ccf_layers > 0) {
        st.mean_vector_field /= st.ccf_layers;
        st.mean_scalar_field /= st.ccf_layers;
        st.mean_extraction /= st.ccf_layers;
        st.mean_connection /= st.ccf_layers;
    }
    st.total_s = clock.elapsed();
    return out;
}

}  // namespace fibrecell::planner
