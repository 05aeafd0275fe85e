// The quality figures of report.json measured on paths whose answers are known by hand.

#include "planner/plan/fibre_quality.hpp"
#include "../fibre/layer_test_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace fibrecell::planner;

namespace {

struct Layer {
    LayerMesh mesh = fibrecell::planner::layer_test::grid_layer(40, 40, 8, 8);
    std::vector<Eigen::Vector3d> v_e =
        std::vector<Eigen::Vector3d>(mesh.triangles.size(), Eigen::Vector3d::UnitX());
    std::vector<double> sigma_e = std::vector<double>(mesh.triangles.size(), 1.0);
    std::vector<std::uint8_t> defined = std::vector<std::uint8_t>(mesh.triangles.size(), 1);

    FibreQualitySums of(const std::vector<Toolpath>& paths) const {
        return fibre_quality(mesh, paths, v_e, sigma_e, defined);
    }
};

Toolpath fibre(std::vector<Eigen::Vector2d> points, bool closed = false) {
    return {PathRole::fibre, closed, std::move(points)};
}

}  // namespace

TEST(FibreQuality, StraightFibreAlongTheTensionTurnsNowhere) {
    const Layer layer;
    const FibreQualitySums q = layer.of({fibre({{2, 20}, {10, 20}, {21, 20}, {38, 20}})});
    EXPECT_NEAR(q.alignment(), 1.0, 1e-12);
    EXPECT_NEAR(q.turning_deg_per_m(), 0.0, 1e-9);
    EXPECT_NEAR(q.turned_length_mm, 36.0, 1e-9);  // 18 chords of 2 mm
}

TEST(FibreQuality, TurningCountsEveryCornerOverTheLengthItCovers) {
    const Layer layer;
    // Three sides of a 10 mm square: two right-angle corners on the 2 mm chord grid, 30 mm.
    const FibreQualitySums q = layer.of({fibre({{5, 5}, {15, 5}, {15, 15}, {5, 15}})});
    EXPECT_NEAR(q.turning_rad, std::numbers::pi, 1e-9);
    EXPECT_NEAR(q.turned_length_mm, 30.0, 1e-9);
    EXPECT_NEAR(q.turning_deg_per_m(), 180.0 / 0.030, 1e-6);
    // A zigzag at +-45 degrees turns 90 degrees at each of its corners: the same per metre
    // whether it is one path or summed from two layers.
    const double s = 2 * std::sqrt(2.0);
    const Toolpath zig = fibre({{5, 5}, {5 + s, 5 + s}, {5 + 2 * s, 5}, {5 + 3 * s, 5 + s}});
    FibreQualitySums two = layer.of({zig});
    two += layer.of({zig});
    EXPECT_NEAR(two.turning_deg_per_m(), layer.of({zig}).turning_deg_per_m(), 1e-9);
    EXPECT_NEAR(layer.of({zig}).turning_deg_per_m(), 2 * 90.0 / (3 * 4.0 / 1000.0), 1e-6);
}

TEST(FibreQuality, ACircleTurnsOnceAroundPerCircumference) {
    const Layer layer;
    std::vector<Eigen::Vector2d> ring;
    const double r = 10;
    for (int i = 0; i < 720; ++i) {
        const double a = 2 * std::numbers::pi * i / 720;
        ring.emplace_back(20 + r * std::cos(a), 20 + r * std::sin(a));
    }
    const FibreQualitySums q = layer.of({fibre(ring, /*closed=*/true)});
    // 360 degrees over 2 pi r, less the one junction at the start the chords do not span.
    EXPECT_NEAR(q.turning_deg_per_m(), 360.0 / (2 * std::numbers::pi * r / 1000.0), 250.0);
    // And the fibre lies across the x tension everywhere but at two points: |cos| averages 2/pi.
    EXPECT_NEAR(q.alignment(), 2 / std::numbers::pi, 0.01);
}
