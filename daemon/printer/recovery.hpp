#pragma once
// What the print runner does with each command and device event, given the print on the cell:
// one table (docs/service.md, "Recovery"), which tests/service/recovery_test.cpp walks cell by
// cell. The runner only carries out the steps it names (print_runner.cpp); the job's own states
// and their transitions are the job store's table (daemon/jobs/job_state.hpp), which has refused
// a command that does not fit the job before the runner hears of it.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::printer {

// The print on the cell as the runner holds it.
enum class OnCell {
    nothing,   // no print on the cell
    printing,  // its session runs
    held,      // paused by the operator or held on a fault: the cell safe, waiting for a resume
};

enum class PrintEvent {
    start,      // job.start, or job.resume of an interrupted job (a re-entry)
    pause,      // job.pause
    resume,     // job.resume of a paused job
    abort,      // job.abort, cell.estop
    fault,      // a device, the sync engine or the job's records failed
    completed,  // the session ran its last event
};

// What is known of the cell and of the event's job when the event comes.
struct Situation {
    OnCell on_cell = OnCell::nothing;
    std::optional<std::int64_t> job_on_cell;  // its id, when on_cell is not nothing
    bool job_ended = false;       // the event's job has ended in the store (a pause that came late)
    bool fault_reported = false;  // the print on the cell is held on a fault already reported
    bool board_down = false;      // the extruder board's link is not active
    bool heaters_off = false;     // the heaters went off while the print was held
    bool tool_lost = false;       // the board restarted while held: its tool is its default one
};

enum class Step {
    start_print,      // load and verify the plan, connect, heat, upload, run: printing
    pause_print,      // the robot paused and waited for to stand, the heaters' pause clock: held
    note_ended,       // a pause for a print that ended meanwhile: said in the log, nothing more
    reconnect_board,  // the board's link opened again; a board that restarted lost heat and tool
    reheat,           // the hotends to the plan's temperatures, waited for
    reselect_tool,    // the head of the last confirmed event selected again
    resume_print,     // the session goes on: printing
    abort_print,      // the session aborted, result.json, the heaters' end
    hold,             // the session paused, the job paused with the fault's reason: held
    finish,           // result.json, the heaters' end: completed (or completed with warnings)
};

struct Decision {
    std::vector<Step> steps;  // in order; empty and no refusal: nothing to do
    std::string refusal;      // not empty: refused with this text, nothing done
};

// The one table: what `event` for job `job` does in situation `s`.
Decision decide(PrintEvent event, std::int64_t job, const Situation& s);

std::string_view to_string(PrintEvent event);
std::string_view to_string(Step step);

}  // namespace fibrecell::daemon::printer
