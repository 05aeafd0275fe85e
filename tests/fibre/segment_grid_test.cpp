// The segment grid behind every "what fibre is near this point" question of the planner: checked
// against all segments, brute force. A query sees every segment nearer than a cell, and a long
// slanted segment is not seen from far off its line only because its bounding box is near.

#include "planner/fibre/segment_grid.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

using namespace fibrecell::planner;

namespace segment_grid_test {

std::set<int> seen_around(const SegmentGrid& grid, const Eigen::Vector2d& p) {
    std::set<int> seen;
    grid.around(p, [&](const TaggedSegment& s) { seen.insert(s.tag); });
    return seen;
}

}  // namespace segment_grid_test

using namespace segment_grid_test;

TEST(SegmentGrid, AQuerySeesEverySegmentNearerThanACell) {
    constexpr double cell = 1.3;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> at(-20, 20), len(0, 25), unit(-1, 1);
    SegmentGrid grid(cell);
    std::vector<TaggedSegment> all;
    for (int i = 0; i < 300; ++i) {
        const Eigen::Vector2d a(at(rng), at(rng));
        Eigen::Vector2d d(unit(rng), unit(rng));
        // Slanted, along the axes, of no length, and ends exactly on cell lines.
        if (i % 10 == 1) d.y() = 0;
        if (i % 10 == 2) d.x() = 0;
        if (i % 10 == 3) d.setZero();
        if (i % 10 == 5) d.x() = 1e-12;  // all but vertical: rounding must not lose a cell
        const Eigen::Vector2d b = i % 10 == 4 ? Eigen::Vector2d(3 * cell, -2 * cell)
                                              : Eigen::Vector2d(a + len(rng) * d);
        const Eigen::Vector2d from = i % 10 == 4 ? Eigen::Vector2d(-5 * cell, 4 * cell) : a;
        all.push_back({from, b, i});
        grid.insert(all.back());
    }
    int near = 0;
    for (int q = 0; q < 4000; ++q) {
        const Eigen::Vector2d p(at(rng), at(rng));
        const std::set<int> seen = seen_around(grid, p);
        for (const TaggedSegment& s : all) {
            if (point_segment_distance(p, s.a, s.b) >= cell) continue;
            ++near;
            ASSERT_TRUE(seen.count(s.tag)) << "segment " << s.tag << " from (" << s.a.transpose()
                                           << ") to (" << s.b.transpose() << ") not seen from ("
                                           << p.transpose() << ")";
            const auto is_it = [&](const TaggedSegment& t) { return t.tag == s.tag; };
            ASSERT_TRUE(grid.any_around(p, is_it));
        }
    }
    EXPECT_GT(near, 10000);  // the queries met many segments
}

TEST(SegmentGrid, ALongSlantedSegmentIsSeenOnlyNearItsLine) {
    SegmentGrid grid(1.0);
    grid.insert({{0, 0}, {100, 100}, 1});
    EXPECT_EQ(seen_around(grid, {50.5, 50}), std::set<int>{1});
    // Inside the segment's bounding box, 35 mm off its line: not visited.
    EXPECT_TRUE(seen_around(grid, {75, 25}).empty());
    EXPECT_FALSE(grid.any_around({25, 75}, [](const TaggedSegment&) { return true; }));
}
