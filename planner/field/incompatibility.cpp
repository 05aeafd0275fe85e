#include "planner/field/incompatibility.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::planner {

std::string_view to_string(IncompatibilityRule rule) {
    switch (rule) {
        case IncompatibilityRule::all_neighbours:
            return "all";
        case IncompatibilityRule::any_neighbour:
            return "any";
        case IncompatibilityRule::majority:
            return "majority";
    }
    return "?";
}

namespace {

bool incompatible(std::uint32_t disagreeing, std::uint32_t neighbours, IncompatibilityRule rule) {
    if (neighbours == 0) return false;
    switch (rule) {
        case IncompatibilityRule::all_neighbours: return disagreeing == neighbours;
        case IncompatibilityRule::any_neighbour: return disagreeing > 0;
        case IncompatibilityRule::majority: return 2 * disagreeing > neighbours;
    }
    return false;
}

}  // namespace

void DotHistogram::add(double dot) {
    const int bin = static_cast<int>(std::floor((dot + 1.0) * 0.5 * bin_count));
    ++counts[static_cast<std::size_t>(std::clamp(bin, 0, bin_count - 1))];
    ++pairs;
}

NeighbourAgreement neighbour_agreement(const std::vector<Eigen::Vector3d>& v_e,
                                       const CsrGraph& neighbours, double eta) {
    NeighbourAgreement a;
    a.disagreeing.assign(v_e.size(), 0);
    a.neighbours.assign(v_e.size(), 0);
    for (std::size_t e = 0; e < v_e.size(); ++e) {
        const int ei = static_cast<int>(e);
        const auto around = neighbours.neighbours(ei);
        a.neighbours[e] = static_cast<std::uint32_t>(around.size());
        // The later half of the sorted list: the earlier neighbours met this pair already.
        for (auto it = std::upper_bound(around.begin(), around.end(), ei); it != around.end();
             ++it) {
            const double dot = v_e[e].dot(v_e[*it]);
            a.dots.add(dot);
            if (dot <= eta) {
                ++a.disagreeing[e];
                ++a.disagreeing[*it];
                ++a.dots.at_most_eta;
            }
        }
    }
    return a;
}

std::vector<std::uint8_t> compatible_directions(const NeighbourAgreement& a,
                                                IncompatibilityRule rule) {
    std::vector<std::uint8_t> defined(a.neighbours.size(), 1);
    for (std::size_t e = 0; e < defined.size(); ++e)
        if (incompatible(a.disagreeing[e], a.neighbours[e], rule)) defined[e] = 0;
    return defined;
}

double removed_fraction(const NeighbourAgreement& a, IncompatibilityRule rule) {
    std::size_t removed = 0;
    for (std::size_t e = 0; e < a.neighbours.size(); ++e)
        removed += incompatible(a.disagreeing[e], a.neighbours[e], rule);
    return static_cast<double>(removed) /
           static_cast<double>(std::max<std::size_t>(1, a.neighbours.size()));
}

std::vector<std::uint8_t> compatible_directions(const std::vector<Eigen::Vector3d>& v_e,
                                                const CsrGraph& neighbours,
                                                const IncompatibilityOptions& options) {
    return compatible_directions(neighbour_agreement(v_e, neighbours, options.eta), options.rule);
}

}  // namespace fibrecell::planner
