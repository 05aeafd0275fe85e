// The print runner's recovery table (daemon/printer/recovery.hpp), walked cell by cell: every
// event in every place of the event's job with respect to the cell, under every combination of
// what the runner knows of the cell, against what docs/service.md ("Recovery") says it does.
#include "daemon/printer/recovery.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace fibrecell::test {
namespace recovery_test {

using daemon::printer::decide;
using daemon::printer::OnCell;
using daemon::printer::PrintEvent;
using daemon::printer::Situation;

constexpr std::int64_t job = 7;    // the event's job
constexpr std::int64_t other = 3;  // another job

const PrintEvent events[] = {PrintEvent::start, PrintEvent::pause,  PrintEvent::resume,
                             PrintEvent::abort, PrintEvent::fault, PrintEvent::completed};
const char* places[] = {"cell_free", "other_on_cell", "printing", "held"};

Situation in_place(const std::string& place) {
    Situation s;
    if (place == "cell_free") return s;
    s.on_cell = place == "held" ? OnCell::held : OnCell::printing;
    s.job_on_cell = place == "other_on_cell" ? other : job;
    return s;
}

// "refused: TEXT", "nothing", or the steps joined by " ".
std::string said(PrintEvent event, const Situation& s) {
    const auto d = decide(event, job, s);
    if (!d.refusal.empty()) return "refused: " + d.refusal;
    if (d.steps.empty()) return "nothing";
    std::string out;
    for (const auto step : d.steps) out += (out.empty() ? "" : " ") + std::string(to_string(step));
    return out;
}

// With nothing else known (no fault reported, the board up, heaters on, the tool kept, the
// event's job not ended): what each event does in each place.
const std::map<std::string, std::string> plain = {
    {"start/cell_free", "start_print"},
    {"start/other_on_cell", "refused: job 3 is on the cell"},
    {"start/printing", "refused: job 7 is on the cell"},
    {"start/held", "refused: job 7 is on the cell"},
    {"pause/cell_free", "refused: job 7 is not on the cell"},
    {"pause/other_on_cell", "refused: job 7 is not on the cell"},
    {"pause/printing", "pause_print"},
    {"pause/held", "nothing"},
    {"resume/cell_free", "refused: job 7 is not on the cell"},
    {"resume/other_on_cell", "refused: job 7 is not on the cell"},
    {"resume/printing", "nothing"},
    {"resume/held", "resume_print"},
    {"abort/cell_free", "nothing"},
    {"abort/other_on_cell", "nothing"},
    {"abort/printing", "abort_print"},
    {"abort/held", "abort_print"},
    {"fault/cell_free", "nothing"},
    {"fault/other_on_cell", "nothing"},
    {"fault/printing", "hold"},
    {"fault/held", "hold"},
    {"completed/cell_free", "nothing"},
    {"completed/other_on_cell", "nothing"},
    {"completed/printing", "finish"},
    {"completed/held", "finish"},
};

// What each thing known changes, and where; everywhere else it changes nothing.
std::string expected(PrintEvent event, const std::string& place, const Situation& s) {
    const std::string cell = std::string(to_string(event)) + "/" + place;
    const bool away = place == "cell_free" || place == "other_on_cell";
    if (event == PrintEvent::pause && away && s.job_ended) return "note_ended";
    if (cell == "fault/held" && s.fault_reported) return "nothing";
    if (cell == "resume/held") {
        if (s.board_down) return "reconnect_board reheat reselect_tool resume_print";
        std::string steps;
        if (s.heaters_off) steps += "reheat ";
        if (s.tool_lost) steps += "reselect_tool ";
        return steps + "resume_print";
    }
    return plain.at(cell);
}

TEST(RecoveryTable, EveryEventInEveryPlaceUnderEverythingKnownDoesWhatTheDocsSay) {
    int cells = 0;
    for (const PrintEvent event : events)
        for (const std::string place : places)
            for (int known = 0; known < 32; ++known) {
                Situation s = in_place(place);
                s.job_ended = (known & 1) != 0;
                s.fault_reported = (known & 2) != 0;
                s.board_down = (known & 4) != 0;
                s.heaters_off = (known & 8) != 0;
                s.tool_lost = (known & 16) != 0;
                EXPECT_EQ(said(event, s), expected(event, place, s))
                    << to_string(event) << " with the job " << place << ", known " << known;
                ++cells;
            }
    EXPECT_EQ(cells, 6 * 4 * 32);
}

}  // namespace recovery_test
}  // namespace fibrecell::test
