// The bundled examples: the fibre guarantees on every CCF layer (no fibre path shorter than the
// cutter distance, no two points of different paths closer than W, every point inside the
// layer's region) and regression figures (layers, fibre length and paths, quality).

#include "planner/job/job_spec.hpp"
#include "planner/layers/outline.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/toolpaths/path_order.hpp"
#include "tests/support/plan_inputs.hpp"
#include "tests/support/shared_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <unordered_map>

using namespace fibrecell::planner;

namespace {

// Points every `step` mm along a path (its vertices included).
std::vector<Eigen::Vector2d> sample(const Toolpath& p, double step) {
    std::vector<Eigen::Vector2d> out;
    const std::size_t n = p.points.size();
    for (std::size_t i = 0; i + 1 < n + (p.closed ? 1 : 0); ++i) {
        const Eigen::Vector2d a = p.points[i], b = p.points[(i + 1) % n];
        const int k = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
        for (int j = 0; j < k; ++j) out.push_back(a + (b - a) * (static_cast<double>(j) / k));
    }
    out.push_back(p.closed ? p.points.front() : p.points.back());
    return out;
}

// Smallest distance between sample points of different paths, through a hash grid.
double min_distance_between_paths(const std::vector<Toolpath>& paths, double cell) {
    struct Sample {
        Eigen::Vector2d p;
        int path;
    };
    std::unordered_map<long long, std::vector<Sample>> grid;
    auto key = [&](long x, long y) {
        return (static_cast<long long>(x) << 32) ^ (y & 0xffffffffLL);
    };
    std::vector<Sample> all;
    for (std::size_t i = 0; i < paths.size(); ++i)
        for (const auto& q : sample(paths[i], cell / 4)) all.push_back({q, static_cast<int>(i)});
    for (const auto& s : all)
        grid[key(std::lround(std::floor(s.p.x() / cell)), std::lround(std::floor(s.p.y() / cell)))]
            .push_back(s);
    double best = std::numeric_limits<double>::infinity();
    for (const auto& s : all) {
        const long cx = std::lround(std::floor(s.p.x() / cell)),
                   cy = std::lround(std::floor(s.p.y() / cell));
        for (long x = cx - 1; x <= cx + 1; ++x)
            for (long y = cy - 1; y <= cy + 1; ++y)
                if (auto it = grid.find(key(x, y)); it != grid.end())
                    for (const auto& t : it->second)
                        if (t.path != s.path) best = std::min(best, (t.p - s.p).norm());
    }
    return best;
}

// Winding number of the outline's loops around p: 1 inside the region, 0 outside.
int winding(const LayerOutline& outline, const Eigen::Vector2d& p) {
    int w = 0;
    for (const auto& loop : outline.loops)
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const Eigen::Vector2d a = loop[i], b = loop[(i + 1) % loop.size()];
            const double cross =
                (b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y());
            if (a.y() <= p.y() && b.y() > p.y() && cross > 0) ++w;
            if (a.y() > p.y() && b.y() <= p.y() && cross < 0) --w;
        }
    return w;
}

double distance_to_outline(const LayerOutline& outline, const Eigen::Vector2d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& loop : outline.loops)
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const Eigen::Vector2d a = loop[i], ab = loop[(i + 1) % loop.size()] - a;
            const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
            best = std::min(best, (a + t * ab - p).norm());
        }
    return best;
}

LayerStageStats check_guarantees(const JobSpec& job) {
    const LayerStageResult r = run_layer_stage(job, fibrecell::test::field_stage_of(job));
    const double w = job.planner.fibre_spacing_mm;
    int fibre_layers = 0;
    for (std::size_t i = 0; i < r.layers.size(); ++i) {
        const ToolpathLayer& layer = r.layers[i];
        if (layer.head != Head::ccf) continue;
        if (!layer.paths.empty()) ++fibre_layers;
        for (const Toolpath& p : layer.paths) {
            EXPECT_GE(path_length(p), job.planner.cutter_distance_mm) << "layer " << i;
            for (const auto& q : p.points)
                EXPECT_TRUE(winding(r.outlines[i], q) == 1 ||
                            distance_to_outline(r.outlines[i], q) < 1e-6)
                    << "layer " << i << " point " << q.transpose() << " outside the region";
        }
        // Sampling at W/4 can hide at most W/8 of a closer approach.
        EXPECT_GT(min_distance_between_paths(layer.paths, w), w - w / 8) << "layer " << i;
    }
    EXPECT_GT(fibre_layers, 0);
    return r.stats;
}

LayerStageStats check_guarantees(const std::string& job_file) {
    return check_guarantees(load_job_file(job_file));
}

// A reference part with its own stress, boundary fibres along the `handle` selection, and a CCF
// layer on every 3rd PLA layer (every layer would triple the time under the sanitizers and add
// no new kind of section). The data is the shared folder's, beside the repository.
JobSpec reference_job(const std::string& name) {
    const std::string dir = (fibrecell::test::reference_fea_dir() / name).string();
    return parse_job("name: " + name + "\nmodel:\n  mesh: " + name + ".tet\n  stress: " + name +
                         "_stress.txt\nregions:\n  handle: {group: handle}\n"
                         "layers:\n  ccf_after_pla: {every: 3, first: 2}\n"
                         "boundary_fibres: [handle]\n",
                     name + ".job.yaml", dir, JobFiles::anywhere);
}

}  // namespace

// Figures measured when the examples were committed (Release and sanitizer builds agree); a
// change beyond the tolerance is a change of the planner's behaviour and must be explained.
TEST(ExampleGuarantees, TensileBar) {
    const LayerStageStats s =
        check_guarantees(FIBRECELL_SOURCE_DIR "/examples/tensile-bar/tensile-bar.job.yaml");
    EXPECT_EQ(s.pla_layers, 5);
    EXPECT_EQ(s.ccf_layers, 5);
    EXPECT_NEAR(s.fibre_length_mm / 1000.0, 7.66, 0.2);
    EXPECT_NEAR(s.fibre_paths, 45, 3);
    EXPECT_NEAR(s.fibre_min_length_mm, 170.0, 1.0);  // every fibre runs the bar's full length
    EXPECT_GT(s.quality.alignment(), 0.99);
    EXPECT_GT(s.quality.density_correlation(), 0.8);
}

TEST(ExampleGuarantees, Loop) {
    const LayerStageStats s = check_guarantees(FIBRECELL_SOURCE_DIR "/examples/loop/loop.job.yaml");
    EXPECT_EQ(s.pla_layers, 13);
    EXPECT_EQ(s.ccf_layers, 13);
    // The paper's Loop: 34.7 m. Ours includes the boundary rings round the outline and the
    // opening (two per layer) and the links along them.
    EXPECT_NEAR(s.fibre_length_mm / 1000.0, 41.2, 1.5);
    EXPECT_NEAR(s.fibre_paths, 186, 10);
    EXPECT_EQ(s.fibre_boundary_paths, 26);
    EXPECT_GT(s.fibre_joins, 80);
    EXPECT_GT(s.quality.alignment(), 0.99);
    EXPECT_GT(s.quality.density_correlation(), 0.75);
}

// The reference data: real meshes whose sections change with height, with islands and holes.
// Skipped when the shared folder is not beside the repository.
TEST(ReferenceGuarantees, Bunnyhead) {
    FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA("bunnyhead");
    const LayerStageStats s = check_guarantees(reference_job("bunnyhead"));
    EXPECT_GT(s.ccf_layers, 5);
    EXPECT_GT(s.fibre_paths, 0);
}

TEST(ReferenceGuarantees, YogaNew) {
    FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA("YogaNew");
    const LayerStageStats s = check_guarantees(reference_job("YogaNew"));
    EXPECT_GT(s.ccf_layers, 5);
    EXPECT_GT(s.fibre_paths, 0);
}
