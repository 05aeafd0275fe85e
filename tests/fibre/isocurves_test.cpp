#include "planner/fibre/isocurves.hpp"
#include "planner/fibre/adaptive_isocurves.hpp"
#include "planner/fibre/curve_spacing.hpp"
#include "planner/fibre/layer_pieces.hpp"
#include "planner/fibre/scalar_field.hpp"

#include "layer_test_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace fibrecell::planner;
using fibrecell::planner::layer_test::centre;
using fibrecell::planner::layer_test::grid_layer;

namespace {

std::vector<double> field_of(const LayerMesh& m, double (*f)(const Eigen::Vector2d&)) {
    std::vector<double> s;
    for (const auto& v : m.vertices) s.push_back(f(v));
    return s;
}

// Distance between neighbouring horizontal fibres, from their y positions.
std::vector<double> sorted_heights(const std::vector<Polyline>& curves) {
    std::vector<double> ys;
    for (const auto& c : curves) ys.push_back(c.points.front().y());
    std::sort(ys.begin(), ys.end());
    return ys;
}

}  // namespace

TEST(Isocurves, LevelLinesOfALinearFieldAreStraightAndSpanTheLayer) {
    const LayerMesh m = grid_layer(30, 10, 15, 5);
    const auto s = field_of(m, [](const Eigen::Vector2d& p) { return 0.3 * p.x() + p.y(); });
    const auto curves = extract_isocurves(m, s, {2.5, 7.0});
    ASSERT_EQ(curves.size(), 2u);
    for (const auto& c : curves) {
        EXPECT_FALSE(c.closed);
        const double iso = c.level == 0 ? 2.5 : 7.0;
        for (const auto& p : c.points) EXPECT_NEAR(0.3 * p.x() + p.y(), iso, 1e-9);
        // From boundary to boundary: both ends on the rectangle's edges.
        for (const auto& end : {c.points.front(), c.points.back()}) {
            const double to_edge = std::min({end.x(), 30 - end.x(), end.y(), 10 - end.y()});
            EXPECT_NEAR(to_edge, 0.0, 1e-9);
        }
    }
}

TEST(Isocurves, ClosedLoopsAroundAPeakAndCurvesThroughVertices) {
    const LayerMesh m = grid_layer(20, 20, 20, 20);
    const auto s =
        field_of(m, [](const Eigen::Vector2d& p) { return -(p - Eigen::Vector2d(10, 10)).norm(); });
    const auto loops = extract_isocurves(m, s, {-5.0});
    ASSERT_EQ(loops.size(), 1u);
    EXPECT_TRUE(loops[0].closed);
    EXPECT_NEAR(polyline_length(loops[0]), 2 * M_PI * 5, 0.5);

    // An isovalue hitting a whole row of vertices: one clean curve, no duplicate points.
    const auto y = field_of(m, [](const Eigen::Vector2d& p) { return p.y(); });
    const auto row = extract_isocurves(m, y, {5.0});
    ASSERT_EQ(row.size(), 1u);
    EXPECT_EQ(row[0].points.size(), 21u);
    EXPECT_NEAR(polyline_length(row[0]), 20.0, 1e-9);
}

TEST(CurveSpacing, MeasuresOnlyNeighbouringLevels) {
    Polyline a{{{0, 0}, {10, 0}}, false, 0};
    Polyline b{{{0, 1.5}, {10, 1.5}}, false, 1};
    Polyline c{{{0, 1.6}, {10, 1.6}}, false, 3};  // close to b, but not a neighbour level
    EXPECT_NEAR(min_neighbour_distance({a, b, c}, 5.0), 1.5, 1e-12);
    EXPECT_NEAR(min_neighbour_distance({a, b}, 1.0), 1.0, 1e-12);  // capped
    Polyline tilted{{{5, 0.7}, {6, 3}}, false, 1};                 // its end comes within 0.7 of a
    EXPECT_NEAR(min_neighbour_distance({a, tilted}, 5.0), 0.7, 1e-12);
}

// The spacing a fibre layer reports counts one path coming back near itself (a hairpin, a cusp)
// once the two stretches are more than 4W apart along it, not the corner where it turns.
TEST(CurveSpacing, FibreSpacingCountsAPathComingBackNearItself) {
    using P = Eigen::Vector2d;
    const std::vector<P> hairpin = {{0, 0}, {10, 0}, {10, 0.6}, {0, 0.6}};  // back at 0.6 mm
    EXPECT_NEAR(min_fibre_spacing({hairpin}, {0}, 4.0, 3.0), 0.6, 1e-12);
    // The same path with the stretches nearer along it than 4 mm: only the corner, not counted.
    const std::vector<P> short_hairpin = {{0, 0}, {1.5, 0}, {1.5, 0.6}, {0, 0.6}};
    EXPECT_NEAR(min_fibre_spacing({short_hairpin}, {0}, 4.0, 3.0), 3.0, 1e-12);
    // A closed ring of radius 5 mm never comes near itself; around the loop the short way.
    std::vector<P> ring;
    for (int k = 0; k < 64; ++k)
        ring.emplace_back(5 * std::cos(k * M_PI / 32), 5 * std::sin(k * M_PI / 32));
    EXPECT_NEAR(min_fibre_spacing({ring}, {1}, 4.0, 3.0), 3.0, 1e-12);
    // Different paths count at any distance along them.
    const std::vector<P> a = {{0, 0}, {10, 0}}, b = {{0, 0.8}, {10, 0.8}};
    EXPECT_NEAR(min_fibre_spacing({a, b}, {0, 0}, 4.0, 3.0), 0.8, 1e-12);
    // Two paths that cross far from their vertices: nothing between them.
    const std::vector<P> up = {{0, -5}, {10, 5}}, down = {{0, 5}, {10, -5}};
    EXPECT_EQ(min_fibre_spacing({up, down}, {0, 0}, 4.0, 3.0), 0.0);
    // A piece's end against the middle of a long segment of another path, beyond the cap's
    // first cell.
    const std::vector<P> longer = {{-20, 1.1}, {20, 1.1}}, tip = {{0, 3}, {0, 2.2}};
    EXPECT_NEAR(min_fibre_spacing({longer, tip}, {0, 0}, 4.0, 3.0), 1.1, 1e-12);
}

// What a layer reports: the same measure, found near W first and farther only when needed.
TEST(CurveSpacing, LayerSpacingIsExactOnEitherSideOfTheNearSearch) {
    const auto at = [](double gap) {
        return std::vector<Toolpath>{{PathRole::fibre, false, {{0, 0}, {10, 0}}},
                                     {PathRole::fibre, false, {{0, gap}, {10, gap}}}};
    };
    for (double gap : {0.7, 1.0, 1.2, 1.3, 2.0, 2.9})
        EXPECT_NEAR(fibre_spacing_mm(at(gap), 1.0), gap, 1e-12) << gap;
    EXPECT_NEAR(fibre_spacing_mm(at(5.0), 1.0), 3.0, 1e-12);  // capped at 3W
    EXPECT_EQ(fibre_spacing_mm({}, 1.0), 0.0);
}

TEST(AdaptiveIsocurves, UniformTensionGivesStraightFibresSpacedJustOverW) {
    const LayerMesh m = grid_layer(30, 10, 30, 20);
    const std::vector<Eigen::Vector2d> u(m.triangles.size(), Eigen::Vector2d(5.0, 0.0));
    const auto s = scalar_field(m, u);
    const AdaptiveIsocurves r = adaptive_isocurves(m, s, {.spacing_mm = 1.0});
    EXPECT_NEAR(r.geodesic_span_mm, 10.0, 1e-9);
    const auto ys = sorted_heights(r.curves);
    ASSERT_EQ(static_cast<int>(ys.size()), r.count);
    EXPECT_GE(r.count, 8);
    for (std::size_t i = 1; i < ys.size(); ++i) {
        EXPECT_GE(ys[i] - ys[i - 1], 1.0 - 1e-9);
        EXPECT_LE(ys[i] - ys[i - 1], 1.25);
    }
    for (const auto& c : r.curves)
        for (const auto& p : c.points) EXPECT_NEAR(p.y(), c.points.front().y(), 1e-9);  // straight
}

// A 60 x 10 mm strip whose s rises along x at slope 1, sixteen times as steep in a band at
// x = 40.5..41 (a strip under 1 MPa with one band at 16 MPa). The isocurves are the vertical lines
// where s takes the levels; their spacing is worked out here in 1-D, and Steps 3-6 are followed
// as the paper states them on those numbers. The spacing is not monotone in n, so stepping down
// from the over-dense count stops far above what a bisection between it and 1 finds.
TEST(AdaptiveIsocurves, StepsDownAsThePaperDoesWhereTheSpacingIsNotMonotone) {
    const LayerMesh m = grid_layer(60, 10, 120, 10);  // columns every 0.5 mm: the band's edges
    const auto S = [](double x) {
        return x <= 40.5 ? x : x <= 41 ? 40.5 + 16 * (x - 40.5) : 48.5 + (x - 41);
    };
    const auto x_of = [](double v) {
        return v <= 40.5 ? v : v <= 48.5 ? 40.5 + (v - 40.5) / 16 : 41 + (v - 48.5);
    };
    std::vector<double> s;
    for (const auto& v : m.vertices) s.push_back(S(v.x()));
    const double w = 1.0, s_max = S(60);
    const auto spacing = [&](int n) {  // d of Eq. 4 in 1-D, capped at 2W as the planner does
        double d = 2 * w;
        for (int i = 0; i + 1 < n; ++i)
            d = std::min(d, x_of((1.5 + i) / n * s_max) - x_of((0.5 + i) / n * s_max));
        return d;
    };
    int n = static_cast<int>(std::ceil(60 / w));  // Step 3: D = 60 mm
    while (spacing(n) > w) n = static_cast<int>(std::ceil(n * spacing(n) / w));  // Step 4
    const int over_dense = n;
    while (n > 1 && spacing(n) <= w) --n;  // Steps 5-6
    int fits = 1, too_dense = over_dense;  // what a bisection would have found
    while (too_dense - fits > 1) {
        const int mid = (fits + too_dense) / 2;
        (spacing(mid) > w ? fits : too_dense) = mid;
    }
    ASSERT_GT(n, fits);

    const AdaptiveIsocurves r = adaptive_isocurves(m, s, {.spacing_mm = w});
    EXPECT_NEAR(r.geodesic_span_mm, 60, 1e-9);
    EXPECT_EQ(r.count, n) << "over-dense at " << over_dense << ", a bisection finds " << fits;
    EXPECT_NEAR(r.min_distance_mm, spacing(n), 1e-9);
    std::vector<double> xs;
    for (const auto& c : r.curves) {
        for (const auto& p : c.points) EXPECT_NEAR(p.x(), c.points.front().x(), 1e-9);  // vertical
        xs.push_back(c.points.front().x());
    }
    std::sort(xs.begin(), xs.end());
    ASSERT_EQ(static_cast<int>(xs.size()), n);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(xs[i], x_of((0.5 + i) / n * s_max), 1e-9);
    // Fast: most counts on the way down are ruled out without extracting them.
    EXPECT_GT(r.counts_ruled_out, 0);
    EXPECT_LT(r.extractions, over_dense - n);
    std::printf(
        "over-dense n %d; step-down n %d (spacing %.2f mm), bisection n %d (%.2f mm); "
        "%d extractions, %d counts ruled out\n",
        over_dense, n, spacing(n), fits, spacing(fits), r.extractions, r.counts_ruled_out);
}

// One crowded band (16 times the stress over 0.5 mm) sets the paper's n for the whole strip; with
// a crowded fraction the rest of the strip gets fibre at about W, the band's crowded curves are
// cut, and no two curves come nearer than W (measured on their x positions: they are vertical).
TEST(AdaptiveIsocurves, ACrowdedBandIsCutBackInsteadOfThinningTheWholeLayer) {
    const LayerMesh m = grid_layer(60, 10, 120, 10);
    const auto S = [](double x) {
        return x <= 40.5 ? x : x <= 41 ? 40.5 + 16 * (x - 40.5) : 48.5 + (x - 41);
    };
    std::vector<double> s;
    for (const auto& v : m.vertices) s.push_back(S(v.x()));
    const double w = 1.0;
    const AdaptiveIsocurves paper = adaptive_isocurves(m, s, {.spacing_mm = w});
    const AdaptiveIsocurves crowded =
        adaptive_isocurves(m, s, {.spacing_mm = w, .crowded_fraction = 0.05});
    std::vector<double> xs;
    for (const auto& c : crowded.curves) {
        for (const auto& p : c.points) EXPECT_NEAR(p.x(), c.points.front().x(), 1e-9);
        EXPECT_NEAR(polyline_length(c), 10, 1e-9);  // cut curves are cut whole here
        xs.push_back(c.points.front().x());
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t i = 1; i < xs.size(); ++i) EXPECT_GE(xs[i] - xs[i - 1], w - 0.005);
    // The strip outside the band is 59.5 mm wide: about one curve per W of it.
    EXPECT_GE(static_cast<int>(xs.size()), 50);
    EXPECT_GT(static_cast<int>(xs.size()), 2 * paper.count);
    EXPECT_GT(crowded.trimmed_mm, 0);
    std::printf("paper n %d; with 5%% crowding n %d, %zu curves kept, %.0f mm cut back\n",
                paper.count, crowded.count, xs.size(), crowded.trimmed_mm);
}

// The counts ruled out without an extraction are never ones the paper's step-down would keep:
// on bumpy fields (steep and shallow stretches, curved level lines) the result is the one of
// extracting every count on the way down.
TEST(AdaptiveIsocurves, RulingOutCountsNeverChangesTheStepDown) {
    const LayerMesh m = grid_layer(40, 12, 50, 15);
    for (const double bump : {0.0, 0.6, 0.9, 0.97}) {
        for (const double tilt : {0.0, 0.35}) {
            std::vector<double> s;
            for (const auto& v : m.vertices)
                s.push_back(v.x() + bump * 4 * std::sin(v.x() / 4 + tilt * v.y()));
            const double w = 1.0;
            const AdaptiveIsocurves r = adaptive_isocurves(m, s, {.spacing_mm = w});
            const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
            const auto d = [&](int n) {
                std::vector<double> iso(static_cast<std::size_t>(n));
                for (int i = 0; i < n; ++i) iso[i] = *lo + (0.5 + i) / n * (*hi - *lo);
                return min_neighbour_distance(extract_isocurves(m, s, iso), 2 * w);
            };
            int n = static_cast<int>(std::ceil(r.geodesic_span_mm / w));
            while (d(n) > w) n = std::max(n + 1, static_cast<int>(std::ceil(n * d(n) / w)));
            while (n > 1 && d(n) <= w) --n;
            EXPECT_EQ(r.count, n) << "bump " << bump << " tilt " << tilt;
        }
    }
}

TEST(AdaptiveIsocurves, ZeroExponentGivesUniformSpacingWhateverTheStress) {
    // p = 0 makes |u| = 1 everywhere: the stress level no longer changes the spacing.
    const LayerMesh m = grid_layer(20, 12, 20, 24);
    const std::vector<Eigen::Vector2d> u(m.triangles.size(), Eigen::Vector2d(1.0, 0.0));
    const auto ys = sorted_heights(adaptive_isocurves(m, scalar_field(m, u)).curves);
    ASSERT_GE(ys.size(), 2u);
    for (std::size_t i = 2; i < ys.size(); ++i) EXPECT_NEAR(ys[i] - ys[i - 1], ys[1] - ys[0], 1e-9);
}

TEST(AdaptiveIsocurves, FibresFollowAQuarterTurn) {
    // Tension running around a corner: the fibres are quarter circles about it.
    const LayerMesh m = grid_layer(
        30, 30, 45, 45, [](const Eigen::Vector2d& c) { return c.norm() > 10 && c.norm() < 28; });
    std::vector<Eigen::Vector2d> u;
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
        const Eigen::Vector2d c = centre(m, f);
        u.emplace_back(Eigen::Vector2d(-c.y(), c.x()).normalized());
    }
    const AdaptiveIsocurves r = adaptive_isocurves(m, scalar_field(m, u), {.spacing_mm = 2.0});
    ASSERT_GE(r.count, 4);
    EXPECT_GT(r.min_distance_mm, 2.0);
    for (const auto& c : r.curves) {
        const double r0 = c.points.front().norm();
        for (const auto& p : c.points) EXPECT_NEAR(p.norm(), r0, 0.3);  // constant radius
    }
}

TEST(AdaptiveIsocurves, NoTensionGivesNoFibres) {
    const LayerMesh m = grid_layer(10, 10, 5, 5);
    const std::vector<double> flat(m.vertices.size(), 0.0);
    const AdaptiveIsocurves r = adaptive_isocurves(m, flat);
    EXPECT_TRUE(r.curves.empty());
    EXPECT_EQ(r.count, 0);
}

TEST(LayerPieces, SplitsSeparateRegionsAndMeasuresEdgePaths) {
    const LayerMesh m = grid_layer(
        30, 10, 15, 5, [](const Eigen::Vector2d& c) { return c.x() < 10 || c.x() > 20; });
    const auto pieces = split_pieces(m);
    ASSERT_EQ(pieces.size(), 2u);
    EXPECT_EQ(pieces[0].mesh.triangles.size() + pieces[1].mesh.triangles.size(),
              m.triangles.size());
    for (const auto& p : pieces) EXPECT_EQ(p.mesh.vertices.size(), 6u * 6);
    // Dijkstra along edges of a 2 mm grid: never shorter than the straight line, and exact
    // along a grid line.
    const LayerMesh& left = pieces[0].mesh;
    const auto origin =
        std::find(left.vertices.begin(), left.vertices.end(), Eigen::Vector2d(0, 0));
    ASSERT_NE(origin, left.vertices.end());
    const auto d = edge_distances(left, {static_cast<int>(origin - left.vertices.begin())});
    for (std::size_t v = 0; v < left.vertices.size(); ++v) {
        EXPECT_GE(d[v], left.vertices[v].norm() - 1e-9);
        if (left.vertices[v].y() == 0) {
            EXPECT_NEAR(d[v], left.vertices[v].x(), 1e-9);
        }
    }
}
