#include "daemon/service/print_plan.hpp"

#include "drivers/abb/rapid/rapid_writer.hpp"
#include "planner/plan/toolpaths_json.hpp"

namespace fibrecell::daemon::service {

namespace abb = drivers::abb;

abb::PrintProgram program_tail(const abb::PrintProgram& program, std::size_t first_move) {
    abb::PrintProgram tail;
    tail.moves.assign(program.moves.begin() + static_cast<std::ptrdiff_t>(first_move),
                      program.moves.end());
    for (const abb::ProgramEvent& e : program.events) {
        if (e.move < first_move) continue;
        abb::ProgramEvent moved = e;
        moved.move -= first_move;
        tail.events.push_back(moved);
    }
    tail.stats = program.stats;
    return tail;
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
    const abb::RapidOutput rapid =
        first_move == 0 ? abb::write_rapid_chunks(p.program, robot)
                        : abb::write_rapid_chunks(program_tail(p.program, first_move), robot);
    for (const abb::RapidModule& m : rapid.modules) p.chunks.push_back({m.file_name, m.text});
    return p;
}

}  // namespace fibrecell::daemon::service
