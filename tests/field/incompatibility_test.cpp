#include "planner/field/incompatibility.hpp"

#include "planner/mesh/adjacency.hpp"
#include "planner/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

using namespace fibrecell::planner;

namespace {

struct Case {
    TetMesh mesh = structured_tet_mesh({.size = {4, 4, 2}, .cells = {4, 4, 2}});
    CsrGraph around = vertex_sharing_neighbours(mesh);
    std::vector<Eigen::Vector3d> v =
        std::vector<Eigen::Vector3d>(mesh.tet_count(), Eigen::Vector3d::UnitX());
};

std::set<int> undefined(const std::vector<std::uint8_t>& defined) {
    std::set<int> out;
    for (std::size_t i = 0; i < defined.size(); ++i)
        if (!defined[i]) out.insert(static_cast<int>(i));
    return out;
}

}  // namespace

TEST(Incompatibility, UniformFieldKeepsEverything) {
    Case c;
    EXPECT_TRUE(undefined(compatible_directions(c.v, c.around)).empty());
}

TEST(Incompatibility, AllNeighboursRuleRemovesExactlyTheOddElement) {
    Case c;
    const int odd = 40;
    c.v[odd] = Eigen::Vector3d::UnitY();  // 90 degrees off every neighbour
    const auto defined =
        compatible_directions(c.v, c.around, {0.5, IncompatibilityRule::all_neighbours});
    EXPECT_EQ(undefined(defined), std::set<int>{odd});
}

TEST(Incompatibility, AnyNeighbourRuleRemovesTheOddElementAndItsNeighbours) {
    Case c;
    const int odd = 40;
    c.v[odd] = Eigen::Vector3d::UnitY();
    const auto defined =
        compatible_directions(c.v, c.around, {0.5, IncompatibilityRule::any_neighbour});
    std::set<int> expected{odd};
    for (int n : c.around.neighbours(odd)) expected.insert(n);
    EXPECT_EQ(undefined(defined), expected);
    EXPECT_GT(expected.size(), 20u);  // vertex sharing reaches far beyond the 4 face neighbours
}

TEST(Incompatibility, ThresholdIsInclusiveAndJudgedOnTheInputField) {
    Case c;
    // Two elements at exactly 60 degrees from the rest: dot = 0.5 <= eta counts as disagreeing.
    const Eigen::Vector3d at60(0.5, std::sqrt(3.0) / 2.0, 0.0);
    const int a = 10;
    c.v[a] = at60;
    auto defined =
        compatible_directions(c.v, c.around, {0.5 + 1e-12, IncompatibilityRule::all_neighbours});
    EXPECT_EQ(undefined(defined), std::set<int>{a});
    defined = compatible_directions(c.v, c.around, {0.49, IncompatibilityRule::all_neighbours});
    EXPECT_TRUE(undefined(defined).empty());
}

TEST(Incompatibility, ElementAgreeingWithOneNeighbourIsKeptUnderThePapersRule) {
    Case c;
    // Two face-adjacent elements both turned to y: each agrees with the other, so "for all
    // neighbours" keeps both, while "any neighbour" removes them.
    const auto nb = face_neighbours(c.mesh);
    const int a = 40;
    int b = -1;
    for (int f : nb[a])
        if (f >= 0) b = f;
    ASSERT_GE(b, 0);
    c.v[a] = c.v[b] = Eigen::Vector3d::UnitY();
    EXPECT_TRUE(undefined(compatible_directions(c.v, c.around)).empty());
    const auto any =
        undefined(compatible_directions(c.v, c.around, {0.5, IncompatibilityRule::any_neighbour}));
    EXPECT_TRUE(any.contains(a) && any.contains(b));
}

TEST(Incompatibility, MajorityRuleNeedsMoreThanHalfTheNeighboursToDisagree) {
    Case c;
    const int odd = 40;
    c.v[odd] = Eigen::Vector3d::UnitY();
    const auto around = c.around.neighbours(odd);
    // Turn just under half of the odd element's neighbours to y as well: it still disagrees
    // with the majority.
    const std::size_t turned = (around.size() - 1) / 2;
    for (std::size_t i = 0; i < turned; ++i) c.v[around[i]] = Eigen::Vector3d::UnitY();
    auto rule = IncompatibilityOptions{0.5, IncompatibilityRule::majority};
    EXPECT_TRUE(undefined(compatible_directions(c.v, c.around, rule)).contains(odd));
    // One more and exactly half or more agree: kept.
    c.v[around[turned]] = Eigen::Vector3d::UnitY();
    c.v[around[turned + 1]] = Eigen::Vector3d::UnitY();
    EXPECT_FALSE(undefined(compatible_directions(c.v, c.around, rule)).contains(odd));
}

TEST(Incompatibility, HistogramCountsEveryNeighbourPairOnceInItsBin) {
    Case c;
    // A field turning smoothly about z, plus one element at 90 degrees to its own neighbours.
    for (std::size_t e = 0; e < c.v.size(); ++e) {
        const double a = 0.2 * static_cast<double>(e % 7);
        c.v[e] = Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
    }
    c.v[40] = Eigen::Vector3d::UnitZ();
    const NeighbourAgreement a = neighbour_agreement(c.v, c.around, 0.5);

    // Brute force over the ordered pairs, each unordered pair seen twice.
    std::array<std::uint64_t, DotHistogram::bin_count> twice{};
    std::uint64_t ordered = 0, ordered_at_most = 0;
    for (int e = 0; e < static_cast<int>(c.v.size()); ++e) {
        std::uint32_t disagreeing = 0;
        for (int n : c.around.neighbours(e)) {
            const double dot = c.v[e].dot(c.v[n]);
            const int bin = std::min(DotHistogram::bin_count - 1,
                                     static_cast<int>(std::floor((dot + 1.0) * 10.0)));
            ++twice[static_cast<std::size_t>(bin)];
            ++ordered;
            if (dot <= 0.5) ++ordered_at_most, ++disagreeing;
        }
        EXPECT_EQ(a.disagreeing[e], disagreeing) << "element " << e;
    }
    EXPECT_EQ(2 * a.dots.pairs, ordered);
    EXPECT_EQ(2 * a.dots.at_most_eta, ordered_at_most);
    for (int b = 0; b < DotHistogram::bin_count; ++b)
        EXPECT_EQ(2 * a.dots.counts[b], twice[b]) << "bin from " << a.dots.lower_edge(b);
    // The odd element's pairs are all at dot 0: the bin [0, 0.1).
    EXPECT_GE(a.dots.counts[10], c.around.neighbours(40).size());
}
