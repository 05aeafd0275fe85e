// Section 4.4's joining of curves: chains from links (path_chains) and Step 4's straight joins of
// close ends (end_joins), on hand-made curves whose right answer is plain to see.
#include "planner/fibre/end_joins.hpp"
#include "planner/fibre/path_chains.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fibrecell::planner;

namespace {

Polyline segment(Eigen::Vector2d a, Eigen::Vector2d b) {
    return {{a, b}, false, 0};
}

// Horizontal runs y = 0, 1.5, 3, ... from x = 0 to 10.
std::vector<Polyline> runs(int n) {
    std::vector<Polyline> out;
    for (int i = 0; i < n; ++i) out.push_back(segment({0, 1.5 * i}, {10, 1.5 * i}));
    return out;
}

}  // namespace

TEST(PathChains, LinksMakeOneChainInLinkOrder) {
    const auto pieces = runs(3);
    // 0 (left to right) -> 1 (right to left) -> 2, with a corner point in the first link.
    const std::vector<Link> links = {{{0, true}, {1, true}, {{11, 0.75}}},
                                     {{2, false}, {1, false}, {}}};  // given backwards
    const auto chains = join_pieces(pieces, links);
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_FALSE(chains[0].closed);
    const std::vector<Eigen::Vector2d> expected = {{0, 0},   {10, 0}, {11, 0.75}, {10, 1.5},
                                                   {0, 1.5}, {0, 3},  {10, 3}};
    EXPECT_EQ(chains[0].points, expected);
}

TEST(PathChains, LinksRoundALoopCloseIt) {
    const auto pieces = runs(2);
    const auto chains =
        join_pieces(pieces, {{{0, true}, {1, true}, {}}, {{1, false}, {0, false}, {}}});
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_TRUE(chains[0].closed);
    EXPECT_EQ(chains[0].points.size(), 4u);
}

TEST(PathChains, UnlinkedAndClosedPiecesPassThrough) {
    auto pieces = runs(2);
    pieces.push_back({{{0, 10}, {1, 10}, {1, 11}}, true, 0});
    const auto chains = join_pieces(pieces, {});
    ASSERT_EQ(chains.size(), 3u);
    EXPECT_TRUE(chains[2].closed);
    EXPECT_THROW(join_pieces(pieces, {{{0, true}, {1, true}, {}}, {{0, true}, {1, false}, {}}}),
                 std::invalid_argument);
}

TEST(EndJoins, CloseEndsMakeASerpentineNotRings) {
    const auto pieces = runs(6);  // ends 1.5 apart on both sides, less than 2W = 2
    const auto links = join_close_ends(pieces, {}, {}, {.max_gap_mm = 2, .clearance_mm = 1});
    EXPECT_EQ(links.size(), 5u);  // the sixth would close a ring
    const auto chains = join_pieces(pieces, links);
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_FALSE(chains[0].closed);
    EXPECT_EQ(chains[0].points.size(), 12u);
}

TEST(EndJoins, EndsTooFarApartOrBlockedStayFree) {
    auto pieces = runs(2);
    EXPECT_TRUE(join_close_ends(pieces, {}, {}, {.max_gap_mm = 1.4}).empty());
    // A third curve across the gap at x = -0.5 blocks the join at x = 0 (clearance 1), not the
    // one at x = 10.
    const std::vector<Polyline> wall = {segment({-0.5, -1}, {-0.5, 3})};
    const auto links = join_close_ends(pieces, {}, wall, {.max_gap_mm = 2, .clearance_mm = 1});
    ASSERT_EQ(links.size(), 1u);
    EXPECT_TRUE(links[0].from.last);
    EXPECT_TRUE(links[0].to.last);
}

TEST(EndJoins, TakenEndsAreNotJoinedAgain) {
    const auto pieces = runs(3);
    const std::vector<Link> taken = {{{0, true}, {1, true}, {}}};
    const auto links = join_close_ends(pieces, taken, {}, {.max_gap_mm = 2, .clearance_mm = 1});
    ASSERT_EQ(links.size(), 1u);  // 1-2 on the left; 0-1 on the left would close a ring
    EXPECT_EQ(join_pieces(pieces,
                          [&] {
                              auto all = taken;
                              all.insert(all.end(), links.begin(), links.end());
                              return all;
                          }())
                  .size(),
              1u);
}

TEST(PathChains, AJoinThatFoldsBackWithinWIsRefused) {
    // Two runs 1.5 apart joined round their right ends: a U-turn that keeps W.
    const auto parallel = runs(2);
    EXPECT_TRUE(join_keeps_spacing(parallel, {}, {{0, true}, {1, true}, {}}, 1.0));
    // A run leaving the join at 10 degrees back along the first: a V-shaped cusp whose arms are
    // closer than W a few millimetres from the join.
    const double a = 10.0 * 3.14159265358979 / 180;
    const std::vector<Polyline> cusp = {
        segment({0, 0}, {10, 0}),
        segment({10, 0.2}, {10 - 10 * std::cos(a), 0.2 + 10 * std::sin(a)})};
    EXPECT_FALSE(join_keeps_spacing(cusp, {}, {{0, true}, {1, false}, {}}, 1.0));
    // The same cusp seen through an earlier link: the fibre is followed across it.
    const std::vector<Polyline> three = {cusp[0], cusp[1], segment({20, 0.2}, {30, 0.2})};
    EXPECT_FALSE(
        join_keeps_spacing(three, {{{1, true}, {2, false}, {}}}, {{0, true}, {1, false}, {}}, 1.0));
}
