#include "planner/field/incompatibility.hpp"

#include <algorithm>

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

NeighbourAgreement neighbour_agreement(const std::vector<Eigen::Vector3d>& v_e,
                                       const CsrGraph& neighbours, double eta) {
    NeighbourAgreement a;
    a.disagreeing.assign(v_e.size(), 0);
    a.neighbours.assign(v_e.size(), 0);
    for (std::size_t e = 0; e < v_e.size(); ++e) {
        const auto around = neighbours.neighbours(static_cast<int>(e));
        a.neighbours[e] = static_cast<std::uint32_t>(around.size());
        for (int n : around)
            if (v_e[e].dot(v_e[n]) <= eta) ++a.disagreeing[e];
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
