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
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
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

// A hash grid of cells `cell` mm wide over whatever is put in it (the test's own, so that the
// measurement shares no code with the planner's).
template <class T>
struct HashGrid {
    double cell;
    std::unordered_map<long long, std::vector<T>> cells;

    static long long key(long x, long y) {
        return (static_cast<long long>(x) << 32) ^ (y & 0xffffffffLL);
    }
    long at(double v) const { return std::lround(std::floor(v / cell)); }
    void add(const Eigen::Vector2d& p, const T& t) {
        cells[key(at(p.x()), at(p.y()))].push_back(t);
    }
    template <class Visit>
    void around(const Eigen::Vector2d& p, Visit visit) const {
        for (long x = at(p.x()) - 1; x <= at(p.x()) + 1; ++x)
            for (long y = at(p.y()) - 1; y <= at(p.y()) + 1; ++y)
                if (auto it = cells.find(key(x, y)); it != cells.end())
                    for (const T& t : it->second) visit(t);
    }
};

struct Spacing {
    double between = std::numeric_limits<double>::infinity();  // points of different paths
    double within = std::numeric_limits<double>::infinity();   // one path, > 4W apart along it
    Eigen::Vector2d between_at{0, 0}, within_at{0, 0};         // where they are
};

// Smallest distances between sample points (every W/4) of a layer's fibre, where they are W or
// less (a grid of W-wide cells: any two points that near are in neighbouring cells).
Spacing measure_spacing(const std::vector<Toolpath>& paths, double w) {
    struct Sample {
        Eigen::Vector2d p;
        int path;
        double along;
    };
    std::vector<double> length;
    HashGrid<Sample> grid{w, {}};
    std::vector<Sample> all;
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const std::vector<Eigen::Vector2d> pts = sample(paths[i], w / 4);
        double along = 0;
        for (std::size_t k = 0; k < pts.size(); ++k) {
            if (k > 0) along += (pts[k] - pts[k - 1]).norm();
            all.push_back({pts[k], static_cast<int>(i), along});
            grid.add(pts[k], all.back());
        }
        length.push_back(along);
    }
    Spacing out;
    for (const Sample& s : all)
        grid.around(s.p, [&](const Sample& t) {
            const double d = (t.p - s.p).norm();
            if (t.path != s.path) {
                if (d < out.between) out.between = d, out.between_at = s.p;
                return;
            }
            double apart = std::abs(t.along - s.along);
            if (paths[s.path].closed) apart = std::min(apart, length[s.path] - apart);
            if (apart > 4 * w && d < out.within) out.within = d, out.within_at = s.p;
        });
    return out;
}

// Winding number of the outline's loops around a point: 1 inside the region, 0 outside. Each
// edge is filed under the horizontal bands (`band` mm high) its y-range spans, so that a point
// counts the crossings of its band's edges only, not of the whole outline.
class OutlineWinding {
  public:
    OutlineWinding(const LayerOutline& outline, double band) : band_(band) {
        for (const auto& loop : outline.loops)
            for (std::size_t i = 0; i < loop.size(); ++i) {
                const Eigen::Vector2d a = loop[i], b = loop[(i + 1) % loop.size()];
                for (long k = at(std::min(a.y(), b.y())); k <= at(std::max(a.y(), b.y())); ++k)
                    bands_[k].push_back({a, b});
            }
    }
    int operator()(const Eigen::Vector2d& p) const {
        const auto it = bands_.find(at(p.y()));
        if (it == bands_.end()) return 0;
        int w = 0;
        for (const auto& [a, b] : it->second) {
            const double cross =
                (b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y());
            if (a.y() <= p.y() && b.y() > p.y() && cross > 0) ++w;
            if (a.y() > p.y() && b.y() <= p.y() && cross < 0) --w;
        }
        return w;
    }

  private:
    long at(double y) const { return std::lround(std::floor(y / band_)); }
    double band_;
    std::unordered_map<long, std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>> bands_;
};

// Distances to a layer's outline, through a grid of its segments (exact below `reach` mm).
class OutlineDistance {
  public:
    OutlineDistance(const LayerOutline& outline, double reach) : grid_{reach, {}} {
        for (const auto& loop : outline.loops)
            for (std::size_t i = 0; i < loop.size(); ++i) {
                const Eigen::Vector2d a = loop[i], b = loop[(i + 1) % loop.size()];
                const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / reach)));
                for (int k = 0; k <= n; ++k) grid_.add(a + (b - a) * (double(k) / n), {a, b});
            }
    }
    double operator()(const Eigen::Vector2d& p) const {
        double best = std::numeric_limits<double>::infinity();
        grid_.around(p, [&](const std::pair<Eigen::Vector2d, Eigen::Vector2d>& s) {
            const Eigen::Vector2d ab = s.second - s.first;
            const double t = std::clamp((p - s.first).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
            best = std::min(best, (s.first + t * ab - p).norm());
        });
        return best;
    }

  private:
    HashGrid<std::pair<Eigen::Vector2d, Eigen::Vector2d>> grid_;
};

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

// What a strategy laid on a part: the stage's figures and the fibre length of each CCF layer.
struct Laid {
    LayerStageStats stats;
    std::vector<double> layer_fibre_mm;  // per CCF layer, in order
};

// Where the strategy puts boundary rings: the field strategy one at 1.5W, field-dense one at
// W/2, contour-zigzag its rings at W/2 + iW.
double ring_target(Strategy strategy, double d, double w) {
    if (strategy == Strategy::field) return 1.5 * w;
    if (strategy == Strategy::field_dense) return w / 2;  // its ribbon's edge on the outline
    return w / 2 + std::max(0.0, std::round((d - w / 2) / w)) * w;
}

// The guarantees of every CCF layer, measured on points resampled from the paths against the
// layer's outline: no fibre path shorter than the cutter distance; no two fibre points closer
// than W, between paths or within one path (more than 4W apart along it); every ribbon inside the
// part (its centreline W/2 from the outline); every boundary ring where the strategy puts it
// (+- 0.1 mm). The figures are printed for the record.
Laid check_guarantees(const JobSpec& job, const FieldStageResult& field) {
    const LayerStageResult r = run_layer_stage(job, field);
    const double w = job.planner.fibre_spacing_mm;
    const std::string strategy(to_string(job.planner.strategy));
    Laid laid{r.stats, {}};
    int fibre_layers = 0;
    Spacing worst;
    std::vector<double> ring_distance;
    double nearest_edge = std::numeric_limits<double>::infinity();
    int outside = 0;
    for (std::size_t i = 0; i < r.layers.size(); ++i) {
        const ToolpathLayer& layer = r.layers[i];
        if (layer.head != Head::ccf) continue;
        if (!layer.paths.empty()) ++fibre_layers;
        const OutlineDistance to_outline(r.outlines[i], 2 * w);
        const OutlineWinding winding(r.outlines[i], 2 * w);
        double layer_length = 0;
        for (const Toolpath& p : layer.paths) {
            layer_length += path_length(p);
            EXPECT_GE(path_length(p), job.planner.cutter_distance_mm) << "layer " << i;
            for (const auto& q : sample(p, w / 4)) {
                const double d = to_outline(q);
                if (winding(q) != 1) ++outside;
                nearest_edge = std::min(nearest_edge, d);
                EXPECT_GE(d, w / 2 - 1e-6) << "layer " << i << " point " << q.transpose()
                                           << " role " << static_cast<int>(p.role) << " closed "
                                           << p.closed << ": the ribbon leaves the part";
                if (p.role != PathRole::fibre_boundary) continue;
                ring_distance.push_back(d);
                EXPECT_NEAR(d, ring_target(job.planner.strategy, d, w), 0.1)
                    << "layer " << i << " ring point " << q.transpose();
            }
        }
        laid.layer_fibre_mm.push_back(layer_length);
        // Sampling at W/4 can hide at most W/8 of a closer approach.
        const Spacing s = measure_spacing(layer.paths, w);
        EXPECT_GT(s.between, w - w / 8)
            << strategy << " layer " << i << ": two paths closer than W at "
            << s.between_at.transpose();
        EXPECT_GT(s.within, w - w / 8)
            << strategy << " layer " << i << ": a path comes back closer than W at "
            << s.within_at.transpose();
        worst.between = std::min(worst.between, s.between);
        worst.within = std::min(worst.within, s.within);
    }
    EXPECT_EQ(outside, 0);
    EXPECT_GT(fibre_layers, 0);
    std::cout << "figures: " << job.name << " " << strategy << " fibre "
              << r.stats.fibre_length_mm / 1000.0 << " m over " << fibre_layers
              << " layers, alignment " << r.stats.quality.alignment() << ", density correlation "
              << r.stats.quality.density_correlation() << ", spacing between " << worst.between
              << " / within " << worst.within << " mm (reported " << r.stats.fibre_min_spacing_mm
              << "), nearest edge " << nearest_edge << " mm, ring distance median "
              << percentile(ring_distance, 0.5) << " p5 " << percentile(ring_distance, 0.05)
              << " p95 " << percentile(ring_distance, 0.95) << " mm, points outside " << outside
              << ", rings joined " << r.stats.fibre_rings_joined << ", dropped short "
              << r.stats.dropped_short << "\n";
    return laid;
}

// Both strategies on one part (one field stage), each checked for the guarantees.
struct Both {
    Laid field, baseline;
};

// baseline_ccf_after: when given, the PLA layers (1-based) that get a baseline CCF layer (on
// a prism every layer has one outline: the baseline's four directions show all it does).
Both check_both(JobSpec job, const FieldStageResult& field,
                const std::vector<int>& baseline_ccf_after = {}) {
    job.planner.strategy = Strategy::field;
    Both both{check_guarantees(job, field), {}};
    job.planner.strategy = Strategy::contour_zigzag;
    if (!baseline_ccf_after.empty()) {
        job.layers.ccf_on_all = false;
        job.layers.ccf_every = 0;
        job.layers.ccf_after_pla = baseline_ccf_after;
    }
    both.baseline = check_guarantees(job, field);
    return both;
}

Both check_both(const JobSpec& job, const std::vector<int>& baseline_ccf_after = {}) {
    return check_both(job, fibrecell::test::field_stage_of(job), baseline_ccf_after);
}

// The smallest per-layer ratio of field to baseline fibre, over the CCF layers both have (in
// order) where the baseline lays fibre; printed with the layer it happens on, and the overall
// ratio per layer.
double min_layer_ratio(const Both& both) {
    double worst = std::numeric_limits<double>::infinity();
    std::size_t at = 0;
    const auto& f = both.field.layer_fibre_mm;
    const auto& b = both.baseline.layer_fibre_mm;
    for (std::size_t i = 0; i < std::min(f.size(), b.size()); ++i)
        if (b[i] > 0 && f[i] / b[i] < worst) worst = f[i] / b[i], at = i;
    std::cout << "figures: field / baseline fibre per CCF layer: min " << worst << " (CCF layer "
              << at << "), overall per layer "
              << (both.field.stats.fibre_length_mm / std::max<std::size_t>(f.size(), 1)) /
                     (both.baseline.stats.fibre_length_mm / std::max<std::size_t>(b.size(), 1))
              << "\n";
    return worst;
}

Both check_both(const std::string& job_file) {
    return check_both(load_job_file(job_file));
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
    const Both both = check_both(fibrecell::test::source_path("examples/tensile-bar/tensile-bar.job.yaml"));
    const LayerStageStats& s = both.field.stats;
    EXPECT_EQ(s.pla_layers, 5);
    EXPECT_EQ(s.ccf_layers, 5);
    EXPECT_NEAR(s.fibre_length_mm / 1000.0, 7.66, 0.2);
    EXPECT_NEAR(s.fibre_paths, 45, 3);
    // Every fibre runs the bar's full length, its ribbon inside the ends: 170 - 2 x W/2.
    EXPECT_NEAR(s.fibre_min_length_mm, 169.0, 0.05);
    EXPECT_GT(s.quality.alignment(), 0.99);
    EXPECT_GT(s.quality.density_correlation(), 0.8);
    // The fibre runs the bar's length and converges into its gauge: 64% of the baseline.
    EXPECT_GE(min_layer_ratio(both), 0.6);
}

// The field-dense strategy on the bar, against the field strategy on the same field stage.
TEST(ExampleGuarantees, TensileBarFieldDense) {
    JobSpec job = load_job_file(fibrecell::test::source_path("examples/tensile-bar/tensile-bar.job.yaml"));
    const FieldStageResult field = fibrecell::test::field_stage_of(job);
    const Laid sparse = check_guarantees(job, field);
    job.planner.strategy = Strategy::field_dense;
    const Laid dense = check_guarantees(job, field);
    EXPECT_EQ(dense.stats.ccf_layers, 5);
    // More fibre than the field strategy's, still along the bar.
    EXPECT_GT(dense.stats.fibre_length_mm, 1.1 * sparse.stats.fibre_length_mm);
    EXPECT_GT(dense.stats.quality.alignment(), 0.98);
}

TEST(ExampleGuarantees, Loop) {
    const Both both = check_both(load_job_file(fibrecell::test::source_path("examples/loop/loop.job.yaml")),
                                 {1, 2, 3, 4});
    const LayerStageStats& s = both.field.stats;
    EXPECT_EQ(s.pla_layers, 13);
    EXPECT_EQ(s.ccf_layers, 13);
    // The paper's Loop: 34.7 m. Ours includes the boundary rings round the outline and the
    // opening (two per layer) and the links along them. The curves stop W/2 short of the pin
    // holes instead of crossing them (more, shorter paths), and joins that would bring a fibre
    // back within W of itself are not made.
    // Where the field converges (round the pins) curves are cut back to W instead of thinning
    // the whole layer (planner.crowded_fraction; without it and at the cap of 99, 40.1 m).
    EXPECT_NEAR(s.fibre_length_mm / 1000.0, 58.0, 2.0);
    EXPECT_NEAR(s.fibre_paths, 322, 15);
    EXPECT_EQ(s.fibre_boundary_paths, 26);
    EXPECT_GT(s.fibre_joins, 60);
    EXPECT_GT(s.quality.alignment(), 0.99);
    EXPECT_GT(s.quality.density_correlation(), 0.7);
    // Both boundaries keep their ring at 1.5W in every CCF layer, as the report says.
    ASSERT_EQ(s.boundaries.size(), 2u);
    for (const auto& [name, b] : s.boundaries) {
        EXPECT_EQ(b.rings, 13) << name;
        EXPECT_GT(b.coverage(), 0.95) << name;
        EXPECT_NEAR(b.ring_distance_quantile(0.5), 1.5, 0.1) << name;
        EXPECT_GT(b.ring_distance_quantile(0.05), 1.4) << name;
        // Curves end on both: the connection joins there (a link counts for one boundary or
        // none), and no ring is short enough to need joining.
        EXPECT_GT(b.joins, 13) << name;
        EXPECT_EQ(b.rings_joined, 0) << name;
    }
    EXPECT_LE(s.boundaries[0].second.joins + s.boundaries[1].second.joins, s.fibre_joins);
    // Short of the 60% the toolpaths issue asks for (41% per layer; 38% at the cap of 99; the
    // paper's method without crowding lays 26%).
    EXPECT_GE(min_layer_ratio(both), 0.38);
}

// The field-dense strategy on the Loop: the guarantees, and the figures issue 37 asks for
// (coverage 0.90, mean path 500 mm: not yet; these floors keep what it has, 0.72).
// Every 4th layer only (the Loop's sections are all alike): the dense layers take 3 s of the
// whole plan in Release, 40 s of the test under ASan.
TEST(ExampleGuarantees, LoopFieldDense) {
    JobSpec job = load_job_file(fibrecell::test::source_path("examples/loop/loop.job.yaml"));
    job.planner.strategy = Strategy::field_dense;
    job.layers.ccf_on_all = false;
    job.layers.ccf_every = 4;
    const Laid dense = check_guarantees(job, fibrecell::test::field_stage_of(job));
    const LayerStageStats& s = dense.stats;
    EXPECT_EQ(s.ccf_layers, 4);
    std::cout << "figures: Loop field-dense coverage " << s.coverage.coverage() << " (covered "
              << s.coverage.covered_fraction() << "), " << s.fibre_paths << " paths\n";
    EXPECT_GT(s.coverage.coverage(), 0.68);
    EXPECT_GT(s.quality.alignment(), 0.97);
}

// The reference data: real meshes whose sections change with height, with islands and holes.
// Skipped when the shared folder is not beside the repository.
TEST(ReferenceGuarantees, Bunnyhead) {
    FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA("bunnyhead");
    const Both both = check_both(reference_job("bunnyhead"));
    EXPECT_GT(both.field.stats.ccf_layers, 5);
    EXPECT_GT(both.field.stats.fibre_paths, 0);
    // Far short of the 60% per layer the toolpaths issue asks for: some layers get no fibre
    // path at all (every isocurve shorter than the cutter distance). 28% overall (17% at the
    // cap of 99); the paper's method without crowding 10%.
    min_layer_ratio(both);
    EXPECT_GT(both.field.stats.fibre_length_mm / both.baseline.stats.fibre_length_mm, 0.25);
    // The handle is the only boundary: every short ring joined onto a stress path is its own.
    ASSERT_EQ(both.field.stats.boundaries.size(), 1u);
    EXPECT_GT(both.field.stats.fibre_rings_joined, 0);
    EXPECT_EQ(both.field.stats.boundaries[0].second.rings_joined,
              both.field.stats.fibre_rings_joined);
    // Its arcs that no path could take, or only into fibre still too short to cut, run on along
    // the edge (at 1.5W, as check_guarantees measured): 94% of the handle's edge has fibre
    // beside it (32% when they were dropped).
    EXPECT_GT(both.field.stats.fibre_rings_extended, 0);
    EXPECT_GT(both.field.stats.boundaries[0].second.coverage(), 0.9);
}

// The field-dense strategy on the bunny's head, with the same guarantees.
TEST(ReferenceGuarantees, BunnyheadFieldDense) {
    FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA("bunnyhead");
    JobSpec job = reference_job("bunnyhead");
    job.planner.strategy = Strategy::field_dense;
    const Laid dense = check_guarantees(job, fibrecell::test::field_stage_of(job));
    std::cout << "figures: bunnyhead field-dense coverage " << dense.stats.coverage.coverage()
              << " (covered " << dense.stats.coverage.covered_fraction() << ")\n";
    EXPECT_GT(dense.stats.coverage.coverage(), 0.5);
}

TEST(ReferenceGuarantees, YogaNew) {
    FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA("YogaNew");
    JobSpec job = reference_job("YogaNew");
    const FieldStageResult field = fibrecell::test::field_stage_of(job);
    const Both both = check_both(job, field);
    EXPECT_GT(both.field.stats.ccf_layers, 5);
    EXPECT_GT(both.field.stats.fibre_paths, 0);
    // As for the bunny head: 19% overall (13% at the cap of 99; the paper's method without
    // crowding 9%).
    min_layer_ratio(both);
    EXPECT_GT(both.field.stats.fibre_length_mm / both.baseline.stats.fibre_length_mm, 0.17);
    // The handle: every arc joined onto a path or run on along the edge; fibre beside all of it
    // (54% when the arcs were dropped).
    ASSERT_EQ(both.field.stats.boundaries.size(), 1u);
    EXPECT_GT(both.field.stats.fibre_rings_extended, 0);
    EXPECT_GT(both.field.stats.boundaries[0].second.coverage(), 0.95);

    // The field-dense strategy on the same part, with the same guarantees; and fibre on every
    // CCF layer whose fibre region holds a path as long as the cutter distance (where the
    // baseline lays one: the top layer's small section gets none from the field strategy).
    job.planner.strategy = Strategy::field_dense;
    const Laid dense = check_guarantees(job, field);
    ASSERT_EQ(dense.layer_fibre_mm.size(), both.baseline.layer_fibre_mm.size());
    for (std::size_t i = 0; i < dense.layer_fibre_mm.size(); ++i) {
        if (both.baseline.layer_fibre_mm[i] > 0) {
            EXPECT_GT(dense.layer_fibre_mm[i], 0) << "CCF layer " << i << " has room for fibre";
        }
    }
    std::cout << "figures: YogaNew coverage: field-dense " << dense.stats.coverage.coverage()
              << " (covered " << dense.stats.coverage.covered_fraction() << "), field "
              << both.field.stats.coverage.coverage() << ", contour-zigzag "
              << both.baseline.stats.coverage.coverage() << "\n";
    // 0.72 of the fibre region (contour-zigzag 1.00, the field strategy 0.19).
    EXPECT_GT(dense.stats.coverage.coverage(), 0.65);
}

