// The coverage figures of report.json on layers whose answers are known by hand: a 20 x 10 mm
// layer, W = 1, so its fibre region (inset W/2) is 19 x 9 mm.

#include "planner/plan/fibre_coverage.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include <Eigen/Geometry>

using namespace fibrecell::planner;

namespace {

const LayerOutline plate20x10{{{{0, 0}, {20, 0}, {20, 10}, {0, 10}}}};
constexpr double plate_region_mm2 = 19.0 * 9.0;

// Straight fibres across the fibre region along x, at the heights given.
std::vector<Toolpath> fibres_along_x(const std::vector<double>& ys) {
    std::vector<Toolpath> paths;
    for (double y : ys) paths.push_back({PathRole::fibre, false, {{0.5, y}, {19.5, y}}});
    return paths;
}

}  // namespace

TEST(FibreCoverage, NineLinesWApartFillTheRegion) {
    const FibreCoverage c = fibre_coverage(plate20x10, fibres_along_x({1, 2, 3, 4, 5, 6, 7, 8, 9}), 1.0);
    EXPECT_NEAR(c.region_mm2, plate_region_mm2, 1e-3);
    EXPECT_NEAR(c.fibre_mm, 9 * 19.0, 1e-9);
    EXPECT_NEAR(c.coverage(), 1.0, 1e-5);
    EXPECT_NEAR(c.covered_fraction(), 1.0, 1e-5);
}

TEST(FibreCoverage, FibreLaidTwiceCountsTwiceInCoverageButOnceInTheCoveredArea) {
    std::vector<Toolpath> twice = fibres_along_x({1, 2, 3, 4, 5, 6, 7, 8, 9});
    const std::vector<Toolpath> again = twice;
    twice.insert(twice.end(), again.begin(), again.end());
    const FibreCoverage c = fibre_coverage(plate20x10, twice, 1.0);
    EXPECT_NEAR(c.coverage(), 2.0, 1e-5);
    EXPECT_NEAR(c.covered_fraction(), 1.0, 1e-5);
}

TEST(FibreCoverage, LinesTwoWApartCoverFiveNinths) {
    const FibreCoverage c = fibre_coverage(plate20x10, fibres_along_x({1, 3, 5, 7, 9}), 1.0);
    EXPECT_NEAR(c.coverage(), 5.0 / 9.0, 1e-5);
    EXPECT_NEAR(c.covered_fraction(), 5.0 / 9.0, 1e-5);
}

TEST(FibreCoverage, FibreOnTheOutlineCoversNothingOfTheRegion) {
    // A ribbon along the outline's edge lies outside where a ribbon fits (its length still counts
    // in the coverage, which is length x W / area).
    const FibreCoverage c = fibre_coverage(plate20x10, {{PathRole::fibre, false, {{0, 0}, {20, 0}}}}, 1.0);
    EXPECT_NEAR(c.covered_mm2, 0.0, 1e-6);
    EXPECT_NEAR(c.coverage(), 20.0 / plate_region_mm2, 1e-9);
}

TEST(FibreCoverage, AHoleGrowsByHalfARibbonWithRoundCornersAndLayersAddUp) {
    const LayerOutline holed{{{{0, 0}, {20, 0}, {20, 10}, {0, 10}}, {{8, 3}, {13, 3}, {13, 8}, {8, 8}}}};
    const double hole = 5.0 * 5.0 + 4 * 5.0 * 0.5 + std::numbers::pi * 0.25;
    const FibreCoverage c = fibre_coverage(holed, fibres_along_x({1, 2}), 1.0);
    EXPECT_NEAR(c.region_mm2, plate_region_mm2 - hole, 0.01);  // the round corners' chords: 0.002 mm
    EXPECT_NEAR(c.covered_mm2, 2 * 19.0, 1e-3);

    FibreCoverage sum = c;
    sum += fibre_coverage(plate20x10, fibres_along_x({1, 2, 3, 4, 5, 6, 7, 8, 9}), 1.0);
    EXPECT_NEAR(sum.coverage(), (2 + 9) * 19.0 / (2 * plate_region_mm2 - hole), 1e-4);
}

TEST(FibreCoverage, ACornerIsCoveredRoundOnItsOutsideAndOnceOnItsInside) {
    // Two legs, 8 and 4 mm: their ribbons overlap in a 0.5 x 0.5 square inside the corner, and
    // the ribbon turns round it outside (a quarter disc of radius W/2).
    const FibreCoverage c =
        fibre_coverage(plate20x10, {{PathRole::fibre, false, {{2, 5}, {10, 5}, {10, 9}}}}, 1.0);
    EXPECT_NEAR(c.covered_mm2, 8 + 4 - 0.25 + std::numbers::pi * 0.25 / 4, 0.01);
}

TEST(FibreCoverage, ATurnedLayerIsMeasuredToAFewPerMille) {
    // The plate and its nine fibres turned by 30 degrees: the scan's rows no longer run along the
    // edges.
    const Eigen::Rotation2Dd turn(0.5236);
    LayerOutline turned = plate20x10;
    for (auto& p : turned.loops[0]) p = turn * p;
    std::vector<Toolpath> paths = fibres_along_x({1, 2, 3, 4, 5, 6, 7, 8, 9});
    for (auto& path : paths)
        for (auto& p : path.points) p = turn * p;
    const FibreCoverage c = fibre_coverage(turned, paths, 1.0);
    EXPECT_NEAR(c.region_mm2, plate_region_mm2, 1e-3);
    EXPECT_NEAR(c.coverage(), 1.0, 1e-5);
    EXPECT_NEAR(c.covered_fraction(), 1.0, 3e-3);
    // Half of them: half covered.
    std::vector<Toolpath> every_other;
    for (std::size_t k = 0; k < paths.size(); k += 2) every_other.push_back(paths[k]);
    EXPECT_NEAR(fibre_coverage(turned, every_other, 1.0).covered_fraction(), 5.0 / 9.0, 3e-3);
}

TEST(FibreCoverage, ALayerWithoutFibreOrRegionHasNone) {
    EXPECT_EQ(fibre_coverage(plate20x10, {}, 1.0).coverage(), 0.0);
    EXPECT_EQ(fibre_coverage(plate20x10, {}, 1.0).covered_fraction(), 0.0);
    const LayerOutline sliver{{{{0, 0}, {20, 0}, {20, 0.8}, {0, 0.8}}}};  // narrower than W
    const FibreCoverage c = fibre_coverage(sliver, fibres_along_x({0.4}), 1.0);
    EXPECT_EQ(c.region_mm2, 0.0);
    EXPECT_EQ(c.coverage(), 0.0);
}
