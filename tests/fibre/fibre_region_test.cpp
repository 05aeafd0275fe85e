// Where a piece may carry fibre (Section 4.4, Steps 1-2 on the true outline): rings at 1.5W
// from the selected boundary, stress fibre kept 2.5W from it and W/2 from every other edge, and
// the link curves at 2.5W, measured here by brute force against the outline polygon.

#include "planner/fibre/fibre_region.hpp"

#include "../toolpaths/toolpath_test_shapes.hpp"
#include "spacing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fibrecell::planner {
namespace {

using test::circle_hole;
using test::rectangle;
using test::segment_distance;

using ::fibrecell::test::W;

std::vector<Segment2> edges_of(const Polygon& loop) {
    std::vector<Segment2> out;
    for (std::size_t i = 0; i < loop.size(); ++i)
        out.push_back({loop[i], loop[(i + 1) % loop.size()]});
    return out;
}

double distance_to(const std::vector<Segment2>& segments, const Eigen::Vector2d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const Segment2& s : segments) best = std::min(best, segment_distance(p, s[0], s[1]));
    return best;
}

// A 40 x 30 plate with a pin hole (r = 5, 24-gon: coarse, as a layer mesh's outline is).
struct Plate {
    Polygon outer = rectangle(0, 0, 40, 30);
    Polygon hole = circle_hole({20, 15}, 5, 24);
    LayerOutline outline{{outer, hole}};
};

TEST(FibreRegion, RingRoundASelectedPinHoleLiesAtOneAndAHalfW) {
    const Plate plate;
    const std::vector<Segment2> hole = edges_of(plate.hole);
    const FibreRegion r = fibre_region(plate.outline, hole, {.spacing_mm = W});
    ASSERT_EQ(r.rings.size(), 1u);
    EXPECT_TRUE(r.rings[0].closed);
    const std::vector<Segment2> all = [&] {
        auto a = edges_of(plate.outer);
        a.insert(a.end(), hole.begin(), hole.end());
        return a;
    }();
    for (std::size_t i = 0; i < r.rings[0].points.size(); ++i) {
        const Eigen::Vector2d p = r.rings[0].points[i];
        EXPECT_NEAR(distance_to(all, p), 1.5 * W, 0.01) << p.transpose();
        const Eigen::Vector2d q = r.rings[0].points[(i + 1) % r.rings[0].points.size()];
        EXPECT_LE((q - p).norm(), W + 1e-9);
    }
    ASSERT_EQ(r.link_curves.size(), 1u);
    for (const auto& p : r.link_curves[0].points) EXPECT_NEAR(distance_to(hole, p), 2.5 * W, 0.01);
}

TEST(FibreRegion, StressFibreKeepsTheBandFromTheSelectedEdgeAndHalfWFromTheRest) {
    const Plate plate;
    const std::vector<Segment2> hole = edges_of(plate.hole);
    const std::vector<Segment2> outer = edges_of(plate.outer);
    const FibreRegion r = fibre_region(plate.outline, hole, {.spacing_mm = W});
    int checked = 0;
    for (double x = 0.05; x < 40; x += 0.1)
        for (double y = 0.05; y < 30; y += 0.1) {
            const Eigen::Vector2d p(x, y);
            if (!test::inside(p, plate.outline)) {
                EXPECT_FALSE(inside_region(r.stress, p)) << p.transpose();
                continue;
            }
            const double to_hole = distance_to(hole, p), to_outer = distance_to(outer, p);
            if (inside_region(r.stress, p)) {
                EXPECT_GE(to_hole, 2.5 * W) << p.transpose();
                EXPECT_GE(to_outer, W / 2) << p.transpose();
                ++checked;
            } else {
                EXPECT_TRUE(to_hole < 2.5 * W + 0.01 || to_outer < W / 2 + 0.01) << p.transpose();
            }
        }
    EXPECT_GT(checked, 90000);
}

TEST(FibreRegion, OnlyTheSelectedPartOfALoopGetsARing) {
    const Plate plate;
    // The plate's bottom edge only: one open ring along it, none round the hole.
    const std::vector<Segment2> bottom = {{plate.outer[0], plate.outer[1]}};
    const FibreRegion r = fibre_region(plate.outline, bottom, {.spacing_mm = W});
    ASSERT_EQ(r.rings.size(), 1u);
    EXPECT_FALSE(r.rings[0].closed);
    for (const auto& p : r.rings[0].points) {
        EXPECT_NEAR(p.y(), 1.5 * W, 0.01);
        EXPECT_GE(p.x(), 1.5 * W - 0.01);
        EXPECT_LE(p.x(), 40 - 1.5 * W + 0.01);
    }
}

TEST(FibreRegion, NothingSelectedKeepsHalfWFromEveryEdge) {
    const Plate plate;
    const FibreRegion r = fibre_region(plate.outline, {}, {.spacing_mm = W});
    EXPECT_TRUE(r.rings.empty());
    EXPECT_TRUE(r.link_curves.empty());
    EXPECT_TRUE(inside_region(r.stress, {0.52, 10}));
    EXPECT_FALSE(inside_region(r.stress, {0.48, 10}));
    EXPECT_TRUE(inside_region(r.stress, {20, 15 - 5.53}));  // outside the hole's inset 24-gon
    EXPECT_FALSE(inside_region(r.stress, {20, 15 - 5.2}));
}

}  // namespace
}  // namespace fibrecell::planner
