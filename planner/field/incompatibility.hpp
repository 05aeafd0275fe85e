#pragma once
// Incompatibility removal (paper Section 4.1, Eq. 2): directions that disagree with their
// vertex-sharing neighbours are marked undefined; sigma_e is kept.

#include "planner/mesh/adjacency.hpp"

#include <Eigen/Core>

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

// v_e: #T re-oriented unit vectors; neighbours: vertex-sharing adjacency. Returns #T flags,
// 1 where v_e stays defined. Every element is judged on the same input field (no cascading),
// and an element without neighbours is kept: there is nothing it disagrees with.
std::vector<std::uint8_t> compatible_directions(const std::vector<Eigen::Vector3d>& v_e,
                                                const CsrGraph& neighbours,
                                                const IncompatibilityOptions& options = {});

}  // namespace fibrecell::planner
