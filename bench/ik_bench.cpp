// IRB 1200 inverse kinematics: solves per second of the single-branch print solver
// (solve_tool0: IK on one cfx branch, J4/J6 unwrapping, limit and singularity checks) on random
// reachable poses, next to the raw eight-branch OPW solve and forward kinematics. Release build;
// numbers are reported only (docs/kinematics.md).
#include "drivers/abb/kinematics/irb1200.hpp"
#include "drivers/abb/kinematics/joint_solver.hpp"

#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace fibrecell::drivers::abb;
using Clock = std::chrono::steady_clock;

namespace {

struct Sample {
    JointVector joints;
    Eigen::Isometry3d tool0;
};

// Random joints inside the limits whose tool0 pose the solver accepts with its defaults (cfx 0).
std::vector<Sample> reachable_samples(const RobotModel& m, int n) {
    std::mt19937 rng(42);
    std::vector<Sample> out;
    while (static_cast<int>(out.size()) < n) {
        JointVector q;
        for (int i = 0; i < 6; ++i)
            q[i] = std::uniform_real_distribution<double>(m.limits.lower_rad[i],
                                                          m.limits.upper_rad[i])(rng);
        const Eigen::Isometry3d t = forward_kinematics(m.geometry, q);
        if (solve_tool0(m, t, q).ok()) out.push_back({q, t});
    }
    return out;
}

// Calls per second of `f` run `n` times.
template <class F>
double per_second(int n, F&& f) {
    const auto t0 = Clock::now();
    for (int i = 0; i < n; ++i) f(i);
    return n / std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main() {
    constexpr int samples_n = 20000, calls = 1'000'000;
    for (const auto variant : {Irb1200Variant::irb1200_7_70, Irb1200Variant::irb1200_5_90}) {
        const RobotModel m = irb1200(variant);
        const std::vector<Sample> s = reachable_samples(m, samples_n);
        double sink = 0;  // keeps the optimiser from dropping the work
        int refused = 0;
        const double solver = per_second(calls, [&](int i) {
            const Sample& x = s[i % samples_n];
            const IkResult r = solve_tool0(m, x.tool0, x.joints);
            refused += !r.ok();
            sink += r.joints[5];
        });
        const double all8 = per_second(calls, [&](int i) {
            for (const auto& q : inverse_kinematics(m.geometry, s[i % samples_n].tool0))
                if (q) sink += (*q)[0];
        });
        const double fk = per_second(calls, [&](int i) {
            sink += forward_kinematics(m.geometry, s[i % samples_n].joints).translation().x();
        });
        std::printf(
            "%s: single-branch solver %.2f M solves/s (%.0f ns/solve, %d refused); "
            "raw OPW, all 8 branches %.2f M poses/s; forward %.2f M/s%s\n",
            std::string(m.name).c_str(), solver / 1e6, 1e9 / solver, refused, all8 / 1e6, fk / 1e6,
            sink == 0.123 ? " " : "");
    }
    return 0;
}
