// The field-dense strategy's gap fill, measured from its points alone (resampled every W/16,
// brute force): it fills what the stripes left bare, along the stress, W from everything laid and
// W/2 inside the layer's outline, and lays nothing shorter than the cutter.

#include "planner/fibre/gap_fill.hpp"

#include "layer_test_mesh.hpp"
#include "path_samples.hpp"
#include "spacing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

using namespace fibrecell::planner;

namespace {

using ::fibrecell::test::W;
using fibrecell::planner::layer_test::grid_layer;

constexpr double cutter = 20;

using Point = ::fibrecell::test::PathSample;

std::vector<Point> resampled(const std::vector<Toolpath>& paths) {
    return ::fibrecell::test::path_samples(paths);
}

double length(const Toolpath& p) {
    double l = 0;
    for (std::size_t k = 0; k + 1 < p.points.size(); ++k) l += (p.points[k + 1] - p.points[k]).norm();
    return l;
}

// A uniform field along `angle` over the whole layer.
LayerField uniform_field(const LayerMesh& m, double angle) {
    LayerField f;
    f.v_f.assign(m.triangles.size(), Eigen::Vector2d(std::cos(angle), std::sin(angle)));
    f.sigma_f.assign(m.triangles.size(), 1.0);
    f.u_f = f.v_f;
    f.defined.assign(m.triangles.size(), 1);
    return f;
}

// The smallest distance between points of two different paths, and of one path more than 4W
// apart along it (LaidFibre's rule for a path coming back on itself), capped at W: pairs are
// looked for in a grid of W cells.
std::pair<double, double> closest_approach(const std::vector<Point>& pts) {
    std::map<std::pair<long, long>, std::vector<std::size_t>> cells;
    const auto cell = [](const Eigen::Vector2d& p) {
        return std::pair<long, long>(std::lround(std::floor(p.x() / W)), std::lround(std::floor(p.y() / W)));
    };
    for (std::size_t i = 0; i < pts.size(); ++i) cells[cell(pts[i].p)].push_back(i);
    double between = W, within = W;
    for (std::size_t a = 0; a < pts.size(); ++a) {
        const auto [cx, cy] = cell(pts[a].p);
        for (long dx = -1; dx <= 1; ++dx)
            for (long dy = -1; dy <= 1; ++dy) {
                const auto it = cells.find({cx + dx, cy + dy});
                if (it == cells.end()) continue;
                for (std::size_t b : it->second) {
                    if (b <= a) continue;
                    const double d = (pts[a].p - pts[b].p).norm();
                    const double apart = ::fibrecell::test::apart_along(pts[a], pts[b]);
                    if (pts[a].path != pts[b].path) between = std::min(between, d);
                    else if (apart > 4 * W) within = std::min(within, d);
                }
            }
    }
    return {between, within};
}

}  // namespace

TEST(GapFill, ABareLayerIsFilledAlongItsStressWApartAndInsideItsOutline) {
    const LayerMesh m = grid_layer(60, 30, 30, 15);
    const double angle = 20 * std::numbers::pi / 180;
    LaidFibre laid(W);
    const GapFill fill = fill_gaps(m, uniform_field(m, angle), {}, laid, {.spacing_mm = W, .cutter_distance_mm = cutter});
    ASSERT_FALSE(fill.paths.empty());
    EXPECT_EQ(fill.gaps, 1u);
    double fibre = 0, along = 0;
    for (const Toolpath& p : fill.paths) {
        EXPECT_EQ(p.role, PathRole::fibre);
        EXPECT_GE(length(p), cutter);
        fibre += length(p);
        for (std::size_t k = 0; k + 1 < p.points.size(); ++k) {
            const Eigen::Vector2d d = p.points[k + 1] - p.points[k];
            along += std::abs(d.dot(Eigen::Vector2d(std::cos(angle), std::sin(angle))));
        }
    }
    // Most of the ribbon area the region offers (59 x 29 mm inside W/2), laid along the stress
    // (the rest is the links between the lines along the outline).
    const double region = (60 - W) * (30 - W);
    EXPECT_GT(fibre * W / region, 0.85) << fibre << " mm";
    EXPECT_GT(along / fibre, 0.9);
    const std::vector<Point> pts = resampled(fill.paths);
    for (const Point& q : pts) {
        EXPECT_GE(q.p.x(), W / 2 - 1e-6);
        EXPECT_LE(q.p.x(), 60 - W / 2 + 1e-6);
        EXPECT_GE(q.p.y(), W / 2 - 1e-6);
        EXPECT_LE(q.p.y(), 30 - W / 2 + 1e-6);
    }
    const auto [between, within] = closest_approach(pts);
    EXPECT_GE(between, 0.995 * W);
    EXPECT_GE(within, 0.995 * W);
}

TEST(GapFill, WhatIsLaidAlreadyKeepsItsPlaceAndTheFillKeepsWFromIt) {
    // A ring along the outline at 1.5 W, and a stress path laid across the middle, W from it.
    const LayerMesh m = grid_layer(60, 30, 30, 15);
    std::vector<Toolpath> laid_paths = {
        {PathRole::fibre_boundary, true, {{1.5, 1.5}, {58.5, 1.5}, {58.5, 28.5}, {1.5, 28.5}}},
        {PathRole::fibre, false, {{2.5, 15}, {30, 12}, {57.5, 15}}}};
    LaidFibre laid(W);
    for (const Toolpath& p : laid_paths) ASSERT_EQ(laid.lay(p.points, p.closed).size(), 1u);
    const GapFill fill = fill_gaps(m, uniform_field(m, 0), laid_paths, laid, {.spacing_mm = W, .cutter_distance_mm = cutter});
    ASSERT_FALSE(fill.paths.empty());
    // Above and below the stress path: two gaps inside the ring, filled along the stress.
    EXPECT_EQ(fill.gaps, 2u);
    std::vector<Toolpath> all = laid_paths;
    all.insert(all.end(), fill.paths.begin(), fill.paths.end());
    double fibre = 0;
    for (const Toolpath& p : fill.paths) fibre += length(p);
    // Inside the ring (1.5 W in), W from it: 55 x 25 mm less the band round the middle path.
    EXPECT_GT(fibre * W / (55 * 25 - 2 * W * 50), 0.8) << fibre << " mm";
    const auto [between, within] = closest_approach(resampled(all));
    EXPECT_GE(between, 0.995 * W);
    EXPECT_GE(within, 0.995 * W);
}

TEST(GapFill, AGapTooSmallForACutterLongPathGetsNothing) {
    // 11 x 5 mm inside W/2: 55 mm^2, lines of about 55 mm in all, none of them 200 mm long.
    const LayerMesh m = grid_layer(12, 6, 6, 3);
    LaidFibre laid(W);
    const GapFill fill = fill_gaps(m, uniform_field(m, 0), {}, laid,
                                   {.spacing_mm = W, .cutter_distance_mm = 200});
    EXPECT_TRUE(fill.paths.empty());
    EXPECT_EQ(fill.gaps, 0u);
}

TEST(GapFill, AGapBetweenTwoRingsIsFilledRoundWithTheStressNotAcrossIt) {
    // Fibre laid round a centre at r = 8 and r = 22 mm, the stress running round too: the annulus
    // between them is best filled with rings W apart; straight lines across it would lie along
    // the stress on average |cos| = 2/pi of their length.
    const LayerMesh m = grid_layer(60, 60, 40, 40);
    const Eigen::Vector2d c(30, 30);
    LayerField field;
    for (std::size_t f = 0; f < m.triangles.size(); ++f) {
        const Eigen::Vector2d r = fibrecell::planner::layer_test::centre(m, static_cast<int>(f)) - c;
        field.v_f.emplace_back(-r.y(), r.x());
        field.sigma_f.push_back(1.0);
    }
    field.u_f = field.v_f;
    field.defined.assign(m.triangles.size(), 1);
    const auto circle = [&](double radius) {
        Toolpath t{PathRole::fibre, true, {}};
        for (int k = 0; k < 400; ++k) {
            const double a = 2 * std::numbers::pi * k / 400;
            t.points.push_back(c + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
        }
        return t;
    };
    const std::vector<Toolpath> laid_paths = {circle(8), circle(22)};
    LaidFibre laid(W);
    for (const Toolpath& p : laid_paths) ASSERT_EQ(laid.lay(p.points, p.closed).size(), 1u);
    const GapFill fill = fill_gaps(m, field, laid_paths, laid, {.spacing_mm = W, .cutter_distance_mm = cutter});
    EXPECT_GE(fill.ringed_gaps, 1u);
    double within = 0, along = 0;
    for (const Toolpath& p : fill.paths) {
        std::vector<Eigen::Vector2d> pts = p.points;
        if (p.closed) pts.push_back(pts.front());
        for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
            const Eigen::Vector2d mid = (pts[k] + pts[k + 1]) / 2 - c;
            if (mid.norm() < 9 || mid.norm() > 21) continue;  // the annulus only
            const Eigen::Vector2d d = pts[k + 1] - pts[k];
            within += d.norm();
            along += std::abs(d.dot(Eigen::Vector2d(-mid.y(), mid.x()).normalized()));
        }
    }
    // The annulus 9..21 mm holds about (21^2 - 9^2) pi / W of fibre: most of it laid, round.
    EXPECT_GT(within, 0.8 * (21 * 21 - 9 * 9) * std::numbers::pi / W);
    EXPECT_GT(along / within, 0.95);
    std::vector<Toolpath> all = laid_paths;
    all.insert(all.end(), fill.paths.begin(), fill.paths.end());
    const auto [between, within_path] = closest_approach(resampled(all));
    EXPECT_GE(between, 0.995 * W);
    EXPECT_GE(within_path, 0.995 * W);
}
