#include "planner/field/incompatibility.hpp"

namespace fibrecell::planner {

std::string_view to_string(IncompatibilityRule rule) {
    return rule == IncompatibilityRule::all_neighbours ? "all" : "any";
}

std::vector<std::uint8_t> compatible_directions(const std::vector<Eigen::Vector3d>& v_e,
                                                const CsrGraph& neighbours,
                                                const IncompatibilityOptions& options) {
    std::vector<std::uint8_t> defined(v_e.size(), 1);
    const bool need_all = options.rule == IncompatibilityRule::all_neighbours;
    for (std::size_t e = 0; e < v_e.size(); ++e) {
        const auto around = neighbours.neighbours(static_cast<int>(e));
        if (around.empty()) continue;
        std::size_t disagreeing = 0;
        for (int n : around)
            if (v_e[e].dot(v_e[n]) <= options.eta) ++disagreeing;
        const bool incompatible = need_all ? disagreeing == around.size() : disagreeing > 0;
        if (incompatible) defined[e] = 0;
    }
    return defined;
}

}  // namespace fibrecell::planner
