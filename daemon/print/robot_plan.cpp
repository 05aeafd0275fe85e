#include "daemon/print/robot_plan.hpp"

#include "planner/stopwatch.hpp"

namespace fibrecell::daemon::print {

std::vector<drivers::abb::RobotLayer> robot_layers(const std::vector<planner::ToolpathLayer>& layers) {
    std::vector<drivers::abb::RobotLayer> out;
    out.reserve(layers.size());
    for (const planner::ToolpathLayer& layer : layers) {
        drivers::abb::RobotLayer& r = out.emplace_back();
        r.index = layer.index;
        r.z = layer.z;
        r.nozzle = layer.head == planner::Head::ccf ? drivers::abb::Nozzle::ccf : drivers::abb::Nozzle::pla;
        r.paths.reserve(layer.paths.size());
        for (const planner::Toolpath& path : layer.paths) r.paths.push_back({path.closed, path.points});
    }
    return out;
}

RobotPlan plan_robot(const std::vector<planner::ToolpathLayer>& layers,
                     const drivers::abb::RobotCellConfig& robot, const PrintSettings& settings,
                     const std::string& job_name) {
    planner::Stopwatch clock;
    RobotPlan out;
    out.program =
        drivers::abb::build_print_program(robot_layers(layers), robot, settings.program_options());
    out.rapid = drivers::abb::write_rapid_chunks(out.program, robot, {.job_name = job_name});
    out.seconds = clock.elapsed();
    return out;
}

void add_robot_report(nlohmann::json& report, const RobotPlan& plan) {
    const auto& s = plan.program.stats;
    report["robot"] = {{"modules", plan.rapid.stats.modules},
                       {"lines", plan.rapid.stats.lines},
                       {"moves", s.moves},
                       {"events", s.events},
                       {"barriers", s.barriers},
                       {"head_switches", s.head_switches},
                       {"duration_s", s.duration_s},
                       {"print_length_m", s.print_length_mm / 1000.0},
                       {"travel_length_m", s.travel_length_mm / 1000.0}};
    report["timings_s"]["rapid"] = plan.seconds;
}

}  // namespace fibrecell::daemon::print
