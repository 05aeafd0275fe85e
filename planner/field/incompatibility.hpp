#pragma once
// Incompatibility removal (paper Section 4.1, Eq. 2): directions that disagree with their
// vertex-sharing neighbours are marked undefined; sigma_e is kept.

#include "planner/mesh/adjacency.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace fibrecell::planner {

enum class IncompatibilityRule {
    // The paper as written: undefined when v_e.v_e* <= eta for ALL neighbours e* (an element
    // that agrees with no neighbour at all).
    all_neighbours,
    // The looser reading: undefined when v_e.v_e* <= eta for ANY neighbour.
    any_neighbour,
    // Between the two: undefined when v_e.v_e* <= eta for MORE THAN HALF of the neighbours.
    majority,
};

std::string_view to_string(IncompatibilityRule rule);

struct IncompatibilityOptions {
    double eta = 0.5;  // dot-product threshold (0.5 = 60 degrees)
    IncompatibilityRule rule = IncompatibilityRule::all_neighbours;
};

// The paper's Fig. 8: v_e.v_e* over every pair of neighbouring elements, in bins 0.1 wide over
// [-1, 1] (the first bin holds -1 exactly, the last +1). eta is chosen where it separates the
// compatible pairs (near +1) from the rest.
struct DotHistogram {
    static constexpr int bin_count = 20;
    std::array<std::uint64_t, bin_count> counts{};
    std::uint64_t pairs = 0;
    std::uint64_t at_most_eta = 0;  // pairs with v_e.v_e* <= eta: the ones Eq. 2 counts

    void add(double dot);
    double lower_edge(int bin) const { return -1.0 + 2.0 * bin / bin_count; }
};

// Per element, how many of its vertex-sharing neighbours e* it disagrees with (v_e.v_e* <= eta)
// out of how many: every reading of Eq. 2 follows from these two counts.
struct NeighbourAgreement {
    std::vector<std::uint32_t> disagreeing;  // #T
    std::vector<std::uint32_t> neighbours;   // #T
    DotHistogram dots;                       // every unordered pair once
};

// v_e: #T re-oriented unit vectors; neighbours: vertex-sharing adjacency, symmetric with sorted
// lists (vertex_sharing_neighbours). One pass over the pairs, each dot product taken once.
NeighbourAgreement neighbour_agreement(const std::vector<Eigen::Vector3d>& v_e,
                                       const CsrGraph& neighbours, double eta);

// #T flags, 1 where v_e stays defined under `rule`. Every element is judged on the same input
// field (no cascading), and an element without neighbours is kept: there is nothing it disagrees
// with.
std::vector<std::uint8_t> compatible_directions(const NeighbourAgreement& agreement,
                                                IncompatibilityRule rule);

// The fraction of elements `rule` undefines.
double removed_fraction(const NeighbourAgreement& agreement, IncompatibilityRule rule);

// Both steps at once.
std::vector<std::uint8_t> compatible_directions(const std::vector<Eigen::Vector3d>& v_e,
                                                const CsrGraph& neighbours,
                                                const IncompatibilityOptions& options = {});

}  // namespace fibrecell::planner
