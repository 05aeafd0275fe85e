#include "planner/plan/layer_stage.hpp"

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
#include <mutex>

namespace fibrecell::planner {
namespace {

struct LayerWork {
    ToolpathLayer layer;
    std::vector<double> sigma;
    std::vector<std::string> warnings;
    int dropped_short = 0;
    int joins = 0;
    int rings_joined = 0;
    double min_spacing = 0;
    FibreLayerTimings timings;
    FibreQualitySums quality;
};

// The part's boundary faces in the job's boundary_fibres regions, on the bed.
SelectedFaces boundary_fibre_selection(const JobSpec& job, const VolumeModel& model,
                                       const TetMesh& placed) {
    if (job.boundary_fibre_regions.empty() || job.planner.strategy != Strategy::field) return {};
    const std::vector<BoundaryTriangle> boundary = boundary_triangles(model.mesh);
    std::vector<BoundaryTriangle> chosen;
    for (const std::string& name : job.boundary_fibre_regions) {
        std::vector<BoundaryTriangle> t = select_triangles(model, boundary, *job.find_region(name));
        if (t.empty())
            throw std::invalid_argument("region '" + name +
                                        "' (boundary_fibres) selects no boundary triangle of the "
                                        "mesh");
        chosen.insert(chosen.end(), t.begin(), t.end());
    }
    return selected_faces(placed, chosen);
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
    fibre.cutter_distance_mm = options.cutter_distance_mm;
    const SelectedFaces boundary_fibre_faces = boundary_fibre_selection(job, field.model, placed);

    std::vector<LayerWork> work(schedule.size());
    std::mutex progress_mutex;  // the sink is called by one task at a time
    std::size_t finished = 0;
    const auto plan_layer = [&](std::size_t i) {
        control.check_cancel();
        const ScheduledLayer& s = schedule[i];
        LayerWork& w = work[i];
        w.layer = {s.index, s.z, s.head, s.thickness, {}};
        out.outlines[i] = layer_outline(out.sections[i]);
        if (s.head == Head::pla) {
            // pla_number is 1-based; the infill angle counts PLA layers from 0.
            w.layer.paths = pla_layer_paths(out.outlines[i], s.pla_number - 1, pla);
        } else if (job.planner.strategy == Strategy::contour_zigzag) {
            auto r = contour_zigzag_paths(out.outlines[i], ccf_ordinal[i], baseline);
            w.layer.paths = std::move(r.paths);
            w.dropped_short = r.dropped_short;
            w.min_spacing = fibre_spacing_mm(w.layer.paths, fibre.spacing_mm);
        } else {
            FibreLayer r = plan_fibre_layer(
                out.sections[i], v_placed, field.field.sigma_e, field.v_defined,
                selected_outline_edges(out.sections[i], boundary_fibre_faces), fibre);
            w.layer.paths = std::move(r.paths);
            w.dropped_short = static_cast<int>(r.dropped_short);
            w.min_spacing = r.min_spacing_mm;
            w.joins = static_cast<int>(r.joins);
            w.rings_joined = static_cast<int>(r.rings_joined);
            w.sigma = std::move(r.field.sigma_f);
            w.warnings = std::move(r.warnings);
            w.timings = r.timings;
        }
        if (s.head == Head::ccf)
            w.quality = fibre_quality(out.sections[i], w.layer.paths, v_placed, field.field.sigma_e,
                                      field.v_defined, {.p = job.planner.p});
        std::lock_guard lock(progress_mutex);
        control.report("layers", static_cast<double>(++finished) / schedule.size());
    };
    SerialExecutor serial;
    (options.executor ? *options.executor : serial).for_each(schedule.size(), plan_layer);

    LayerStageStats& st = out.stats;
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
        st.fibre_joins += w.joins;
        st.fibre_rings_joined += w.rings_joined;
        if (w.min_spacing > 0)
            st.fibre_min_spacing_mm = st.fibre_min_spacing_mm == 0
                                          ? w.min_spacing
                                          : std::min(st.fibre_min_spacing_mm, w.min_spacing);
        st.mean_vector_field += w.timings.vector_field;
        st.mean_scalar_field += w.timings.scalar_field;
        st.mean_extraction += w.timings.extraction;
        st.mean_connection += w.timings.connection;
        st.quality += w.quality;
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
