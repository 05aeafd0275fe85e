#include "daemon/service/print_plan.hpp"

#include "drivers/abb/rapid/rapid_writer.hpp"
#include "planner/plan/toolpaths_json.hpp"

#include <stdexcept>
#include <string>

namespace fibrecell::daemon::service {

namespace abb = drivers::abb;

abb::PrintProgram program_tail(const abb::PrintProgram& program, std::size_t first_move,
                               std::int64_t first_event) {
    abb::PrintProgram tail;
    tail.moves.assign(program.moves.begin() + static_cast<std::ptrdiff_t>(first_move),
                      program.moves.end());
    for (const abb::ProgramEvent& e : program.events) {
        if (e.move < first_move || e.sequence < first_event) continue;
        abb::ProgramEvent moved = e;
        moved.move -= first_move;
        tail.events.push_back(moved);
    }
    tail.stats = program.stats;
    return tail;
}

abb::PrintProgram reentry_program(const abb::PrintProgram& program, const jobs::ResumePoint& resume) {
    // build_print_program ends every travel above the next path start, then approaches.
    if (resume.first_move == 0 || resume.first_move >= program.moves.size())
        throw std::invalid_argument("re-entry: move " + std::to_string(resume.first_move) +
                                    " is no approach after a travel");
    abb::PrintProgram run = program_tail(program, resume.first_move - 1, resume.first_event);
    abb::ProgramMove& rise = run.moves.front();
    rise.role = abb::MoveRole::travel;
    rise.joint = false;  // straight up and over, not a joint move's curve
    rise.fine = true;
    rise.zone_mm = 0;
    rise.length_mm = 0;  // from wherever the robot was held
    return run;
}

PrintPlan load_print_plan(const std::filesystem::path& job_file, const std::filesystem::path& plan_dir,
                          const abb::RobotCellConfig& robot, std::optional<std::int64_t> last_confirmed) {
    PrintPlan p;
    p.job = planner::load_job_file(job_file.string());
    const planner::ToolpathsFile toolpaths =
        planner::read_toolpaths_json((plan_dir / "toolpaths.json").string());
    p.layers = toolpaths.layers.size();
    abb::ProgramOptions options;
    options.pla_speed_mm_s = p.job.process.pla.speed_mm_s;
    options.ccf_speed_mm_s = p.job.process.ccf.speed_mm_s;
    options.cutter_distance_mm = p.job.planner.cutter_distance_mm;
    p.program = abb::build_print_program(toolpaths.layers, robot, options);

    std::size_t first_move = 0;
    if (last_confirmed) {
        p.resume = jobs::resume_point(p.program, *last_confirmed);
        if (!p.resume->nothing_left) {
            first_move = p.resume->first_move;
            p.first_event = p.resume->first_event;
            p.skip_events = p.resume->done_in_unit;
        } else {
            p.first_event = static_cast<std::int64_t>(p.program.events.size()) + 1;
        }
    }
    // A re-entry first lifts straight up by the travel clearance, wherever the robot was held.
    const abb::RapidOutput rapid =
        first_move == 0
            ? abb::write_rapid_chunks(p.program, robot)
            : abb::write_rapid_chunks(reentry_program(p.program, *p.resume), robot,
                                      {.reentry_lift_mm = robot.motion.safe_height_mm});
    for (const abb::RapidModule& m : rapid.modules) p.chunks.push_back({m.file_name, m.text});
    return p;
}

}  // namespace fibrecell::daemon::service
