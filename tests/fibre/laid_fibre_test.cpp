// Laying fibre W apart: what crowds fibre already laid, or the path itself further than 4W back
// along it, is cut; measured here on points resampled from the output, brute force.

#include "planner/fibre/laid_fibre.hpp"
#include "path_samples.hpp"
#include "spacing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace fibrecell::planner;

namespace {

using ::fibrecell::test::W;

using Sample = ::fibrecell::test::PathSample;

std::vector<Sample> samples(const std::vector<LaidPiece>& pieces, int first_path = 0) {
    return ::fibrecell::test::path_samples(pieces, first_path);
}

// Smallest distance between samples of different paths, or of one path more than 4W apart
// along it (open paths only here).
double spacing(const std::vector<Sample>& s) {
    double best = 1e9;
    for (std::size_t a = 0; a < s.size(); ++a)
        for (std::size_t b = a + 1; b < s.size(); ++b)
            if (s[a].path != s[b].path || ::fibrecell::test::apart_along(s[a], s[b]) > 4 * W)
                best = std::min(best, (s[a].p - s[b].p).norm());
    return best;
}

std::vector<Eigen::Vector2d> line(Eigen::Vector2d a, Eigen::Vector2d b) {
    return {a, b};
}

double length(const LaidPiece& p) {
    double l = 0;
    for (std::size_t k = 1; k < p.points.size(); ++k) l += (p.points[k] - p.points[k - 1]).norm();
    return l;
}

}  // namespace

TEST(LaidFibre, APathBesideLaidFibreIsCutWhereItComesWithinW) {
    LaidFibre laid(W);
    const auto first = laid.lay(line({0, 0}, {20, 0}), false);
    ASSERT_EQ(first.size(), 1u);
    // 0.6 mm beside the first over x = 10..20, clear of it beyond x = 20.8.
    const auto second = laid.lay(line({10, 0.6}, {30, 0.6}), false);
    ASSERT_EQ(second.size(), 1u);
    EXPECT_NEAR(second[0].points.front().x(), 20 + std::sqrt(W * W - 0.36), W / 4);
    EXPECT_DOUBLE_EQ(second[0].points.back().x(), 30);
    std::vector<LaidPiece> all = first;
    all.insert(all.end(), second.begin(), second.end());
    EXPECT_GE(spacing(samples(all)), W - 0.01);
}

TEST(LaidFibre, AHairpinTighterThanWKeepsOnlyWhatIsWithin4WOfTheTurn) {
    // Out along y = 0, a half turn of radius 0.3 mm, back along y = 0.6.
    std::vector<Eigen::Vector2d> hairpin;
    for (int k = 0; k <= 20; ++k) hairpin.emplace_back(20 - k, 0);
    for (int k = 1; k < 16; ++k) {
        const double a = -std::numbers::pi / 2 - std::numbers::pi * k / 16;
        hairpin.emplace_back(0.3 * std::cos(a), 0.3 + 0.3 * std::sin(a));
    }
    for (int k = 0; k <= 20; ++k) hairpin.emplace_back(k, 0.6);
    LaidFibre laid(W);
    const auto pieces = laid.lay(hairpin, false);
    ASSERT_EQ(pieces.size(), 1u);  // the rest of the way back crowds the way out: dropped
    // Back at x = b, the way out at x = a lies sqrt((a - b)^2 + 0.36) away and turn + a + b
    // along the path: within W (|a - b| < 0.8) and more than 4W along first from
    // b = (4W - turn - 0.8) / 2 (the check's W/4 samples may stop it a little sooner).
    const double turn = std::numbers::pi * 0.3;
    const double kept_back = (4 * W - turn - 0.8) / 2;
    EXPECT_GT(length(pieces[0]), 20 + turn + kept_back - W / 2);
    EXPECT_LT(length(pieces[0]), 20 + turn + kept_back + W / 2);
    EXPECT_GE(spacing(samples(pieces)), W - 0.01);
}

TEST(LaidFibre, ALoopClearOfEverythingStaysClosedAndOneAcrossLaidFibreIsCutOpen) {
    std::vector<Eigen::Vector2d> circle;
    for (int k = 0; k < 64; ++k) {
        const double a = 2 * std::numbers::pi * k / 64;
        circle.emplace_back(10 * std::cos(a), 10 * std::sin(a));
    }
    LaidFibre laid(W);
    const auto loop = laid.lay(circle, true);
    ASSERT_EQ(loop.size(), 1u);
    EXPECT_TRUE(loop[0].closed);
    EXPECT_EQ(loop[0].points, circle);  // its own vertices, not the check's samples

    LaidFibre crossed(W);
    const auto across = crossed.lay(line({-20, 0.3}, {-5, 0.3}), false);
    const auto cut = crossed.lay(circle, true);
    ASSERT_EQ(cut.size(), 1u);
    EXPECT_FALSE(cut[0].closed);
    std::vector<LaidPiece> all = across;
    all.insert(all.end(), cut.begin(), cut.end());
    const std::vector<Sample> s = samples(all);
    // Between the two paths W; the cut-open loop's own ends are W apart too.
    EXPECT_GE(spacing(s), W - 0.01);
    EXPECT_GE((cut[0].points.front() - cut[0].points.back()).norm(), W - 0.01);
}

TEST(LaidFibre, PiecesShorterThanTheMinimumAreDroppedCountedAndNotLaid) {
    LaidFibre laid(W);
    laid.lay(line({0, 0}, {20, 0}), false);
    // Crowds the first over x = 5..15: leaves pieces of about 4 mm either side.
    EXPECT_TRUE(laid.lay(line({1, 0.5}, {19, 0.5}), false, 5.0).empty());
    EXPECT_EQ(laid.dropped_short(), 0);  // wholly within W of the first: nothing to drop
    EXPECT_TRUE(laid.lay(line({-5, 0.5}, {0, 0.5}), false, 5.0).empty());
    EXPECT_EQ(laid.dropped_short(), 1);  // about 4.1 mm clear of the first: shorter than 5
    EXPECT_NEAR(laid.dropped_short_mm(), 4.134, W / 4);  // to x = -sqrt(W^2 - 0.5^2), a W/4 step
    // What was dropped was not laid: a path through it is whole.
    const auto through = laid.lay(line({-4, 0.6}, {-4, 10}), false);
    ASSERT_EQ(through.size(), 1u);
    EXPECT_NEAR(length(through[0]), 9.4, 1e-9);
}
