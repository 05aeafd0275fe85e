#include "daemon/robot_plan.hpp"

#include "planner/stopwatch.hpp"

namespace fibrecell::daemon {

RobotPlan plan_robot(const planner::JobSpec& job, const std::vector<planner::ToolpathLayer>& layers,
                     const drivers::abb::RobotCellConfig& robot,
                     const std::filesystem::path& rapid_dir) {
    planner::Stopwatch clock;
    RobotPlan out;
    drivers::abb::ProgramOptions options;
    options.pla_speed_mm_s = job.process.pla.speed_mm_s;
    options.ccf_speed_mm_s = job.process.ccf.speed_mm_s;
    options.cutter_distance_mm = job.planner.cutter_distance_mm;
    out.program = drivers::abb::build_print_program(layers, robot, options);
    const drivers::abb::RapidOutput rapid = drivers::abb::write_rapid_chunks(out.program, robot);
    drivers::abb::write_rapid_directory(rapid, rapid_dir);
    out.rapid = rapid.stats;
    out.seconds = clock.elapsed();
    return out;
}

void add_robot_report(nlohmann::json& report, const RobotPlan& plan) {
    const auto& s = plan.program.stats;
    report["robot"] = {{"modules", plan.rapid.modules},
                       {"lines", plan.rapid.lines},
                       {"moves", s.moves},
                       {"events", s.events},
                       {"barriers", s.barriers},
                       {"head_switches", s.head_switches},
                       {"duration_s", s.duration_s},
                       {"print_length_m", s.print_length_mm / 1000.0},
                       {"travel_length_m", s.travel_length_mm / 1000.0}};
    report["timings_s"]["rapid"] = plan.seconds;
}

}  // namespace fibrecell::daemon
