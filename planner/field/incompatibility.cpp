#include "planner/field/incompatibility.hpp"

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

std::vector<std::uint8_t> compatible_directions(const std::vector<Eigen::Vector3d>& v_e,
                                                const CsrGraph& neighbours,
                                                const IncompatibilityOptions& options) {
    std::vector<std::uint8_t> defined(v_e.size(), 1);
    for (std::size_t e = 0; e < v_e.size(); ++e) {
        const auto around = neighbours.neighbours(static_cast<int>(e));
        if (around.empty()) continue;
        std::size_t disagreeing = 0;
        for (int n : around)
            if (v_e[e].dot(v_e[n]) <= options.eta) ++disagreeing;
        bool incompatible = false;
        switch (options.rule) {
            case IncompatibilityRule::all_neighbours:
                incompatible = disagreeing == around.size();
                break;
            case IncompatibilityRule::any_neighbour:
                incompatible = disagreeing > 0;
                break;
            case IncompatibilityRule::majority:
                incompatible = 2 * disagreeing > around.size();
                break;
        }
        if (incompatible) defined[e] = 0;
    }
    return defined;
}

}  // namespace fibrecell::planner
