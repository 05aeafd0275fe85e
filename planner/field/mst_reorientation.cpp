#include "planner/field/mst_reorientation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>

namespace fibrecell::planner {
namespace {

struct Candidate {
    double weight;  // 1 - |v_from . v_to|
    int to;
    int from;
    bool operator>(const Candidate& o) const { return weight > o.weight; }
};

}  // namespace

MstReorientationResult mst_reorient(std::vector<Eigen::Vector3d>& v_e,
                                    const std::vector<double>& sigma_e,
                                    const FaceNeighbours& neighbours, const StepControl& control) {
    const int n = static_cast<int>(v_e.size());
    MstReorientationResult result;
    result.parent.assign(n, -1);
    std::vector<char> in_tree(n, 0);

    std::vector<int> seeds(n);
    std::iota(seeds.begin(), seeds.end(), 0);
    std::stable_sort(seeds.begin(), seeds.end(),
                     [&](int a, int b) { return sigma_e[a] > sigma_e[b]; });

    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> frontier;
    auto push_neighbours = [&](int e) {
        for (int f : neighbours[e]) {
            if (f < 0 || in_tree[f]) continue;
            frontier.push({1.0 - std::abs(v_e[e].dot(v_e[f])), f, e});
        }
    };

    control.report("mst_reorientation", 0.0);
    int joined = 0;
    for (int seed : seeds) {
        if (in_tree[seed]) continue;
        ++result.components;
        in_tree[seed] = 1;
        ++joined;
        push_neighbours(seed);
        while (!frontier.empty()) {
            const Candidate c = frontier.top();
            frontier.pop();
            if (in_tree[c.to]) continue;  // a cheaper edge reached it first
            in_tree[c.to] = 1;
            result.parent[c.to] = c.from;
            if (v_e[c.from].dot(v_e[c.to]) < 0.0) {
                v_e[c.to] = -v_e[c.to];
                ++result.flipped;
            }
            push_neighbours(c.to);
            if (++joined % 65536 == 0) {
                control.check_cancel();
                control.report("mst_reorientation", static_cast<double>(joined) / n);
            }
        }
    }
    control.report("mst_reorientation", 1.0);
    return result;
}

}  // namespace fibrecell::planner
