#pragma once
// What a print of a planned job runs, loaded from its plan directory and nothing else: the
// manifest verified against the files and the cell (manifest.hpp), the settings and chunk table
// of print.json, the program of program.json, and the RAPID chunks exactly as planned. A run
// that re-enters an interrupted print (resume_point.hpp) uploads the planned chunks from the
// interrupted one on; only that one is rewritten, from the plan's own moves and joints, to start
// with the lift and the travel to the unit's start (docs/jobs.md, "Re-entry").

#include "daemon/cell/cell_config.hpp"
#include "daemon/print/manifest.hpp"
#include "daemon/print/print_file.hpp"
#include "daemon/print/resume_point.hpp"
#include "drivers/abb/fcmain/fc_main_control.hpp"
#include "drivers/abb/kinematics/joint_vector.hpp"
#include "drivers/abb/program/print_program.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

namespace fibrecell::daemon::print {

struct PrintPlan {
    PrintFile print;                                // settings, chunk table, layer count
    drivers::abb::PrintProgram program;             // the whole job (events by sequence)
    std::vector<drivers::abb::JointVector> joints;  // per move, as planned
    std::vector<drivers::abb::ChunkFile> chunks;    // this run's modules, in order
    int first_chunk = 1;                            // FcMain's first chunk of this run (1-based)
    int chunk_count = 0;                            // the job's chunks
    std::int64_t first_event = 1;                   // the run's first event
    std::vector<std::int64_t> skip_events;          // done before, passed again without feed
    std::optional<ResumePoint> resume;              // set when the run re-enters
    std::size_t layers() const { return print.layers; }
};

// plan_dir: the job's plan directory. With `last_confirmed` set, the run re-enters after that
// event (no chunk at all when nothing is left to print), in the middle of the interrupted fibre
// path when `fed` says how far its feed went (resume_point). Throws PlanRefused (manifest.hpp: the
// plan is incomplete, damaged, or for a cell that changed), std::invalid_argument for a plan file
// that does not read, RapidWriteError when the re-entry chunk cannot be written.
PrintPlan load_print_plan(const std::filesystem::path& plan_dir, const CellConfig& cell,
                          std::optional<std::int64_t> last_confirmed = std::nullopt,
                          std::optional<FibreFed> fed = std::nullopt);

// Moves [first_move, end_move) of `program` (end 0: to the end) and the events on them from
// `first_event` on, their sequence numbers kept (the robot reports them as in the whole program).
drivers::abb::PrintProgram program_tail(const drivers::abb::PrintProgram& program,
                                        std::size_t first_move, std::size_t end_move = 0,
                                        std::int64_t first_event = 1);

// The moves of a run that re-enters at `resume`, up to `end_move` (exclusive, 0: the end). The
// robot stands where it was held, somewhere in the interrupted unit at that layer's height. The
// chunk first lifts it straight up by the travel clearance; this program's first move is then a
// straight move to the unit's travel point above its path start (where the whole program's
// travel there ends), and the approach comes straight down: the robot never moves sideways at
// the layer's height.
//
// A fibre path re-entered `fibre_fed_mm` along it: the first move rises to above that point, the
// approach comes down onto it, the fibre_start's barrier (a new thread) stands before the rest of
// the move it falls on, and the path goes on as planned.
drivers::abb::PrintProgram reentry_program(const drivers::abb::PrintProgram& program,
                                           const ResumePoint& resume, std::size_t end_move = 0);

// The program move a re-entry's first chunk is cut from: the travel into the unit, or the print
// move of the fibre path that its fed fibre ends on.
std::size_t reentry_move(const drivers::abb::PrintProgram& program, const ResumePoint& resume);

}  // namespace fibrecell::daemon::print
