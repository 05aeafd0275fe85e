#pragma once
// What a print of a planned job runs: the job's print program (from its toolpaths.json and the
// cell's robot configuration, the same way planning made it) and the RAPID chunk modules of the
// run, for the whole program or, when resuming an interrupted print, from its re-entry point
// (daemon/jobs/resume_point.hpp) on. The chunks are built fresh from the program so that the two
// always agree.

#include "daemon/jobs/resume_point.hpp"
#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/fcmain/fc_main_control.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "planner/job/job_spec.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

namespace fibrecell::daemon::service {

struct PrintPlan {
    planner::JobSpec job;
    drivers::abb::PrintProgram program;         // the whole job (events by sequence)
    std::vector<drivers::abb::ChunkFile> chunks;  // this run's RAPID modules
    std::int64_t first_event = 1;               // the run's first event
    std::vector<std::int64_t> skip_events;      // done before, passed again without feed
    std::optional<jobs::ResumePoint> resume;    // set when the run re-enters an interrupted print
    std::size_t layers = 0;
};

// job_file: the job's input/job.yaml; plan_dir: its plan directory (toolpaths.json). With
// `last_confirmed` set, the run re-enters after that event. Throws config::ConfigError,
// planner::InputError, drivers::abb::PrintProgramError or RapidWriteError naming what is wrong.
PrintPlan load_print_plan(const std::filesystem::path& job_file, const std::filesystem::path& plan_dir,
                          const drivers::abb::RobotCellConfig& robot,
                          std::optional<std::int64_t> last_confirmed = std::nullopt);

// The program from `first_move` on, for the RAPID writer: later moves and the events on them
// from `first_event` on, with their sequence numbers kept (the robot reports them as in the whole
// program).
drivers::abb::PrintProgram program_tail(const drivers::abb::PrintProgram& program,
                                        std::size_t first_move, std::int64_t first_event = 1);

// The program of a run that re-enters at `resume`. The robot stands where it was held, somewhere
// in the interrupted unit at that layer's height. Its chunks (load_print_plan) first lift it
// straight up by the travel clearance; this program's first move is then a MoveL to the unit's
// travel point above its path start (where the whole program's travel there ends), and the
// approach comes straight down: the robot never moves sideways at the layer's height.
drivers::abb::PrintProgram reentry_program(const drivers::abb::PrintProgram& program,
                                           const jobs::ResumePoint& resume);

}  // namespace fibrecell::daemon::service
