#pragma once
// What a board really did, against the plan it was given: the pin edges gt2560-avr logged
// (--edge-log: "<simulated s> <pin> <0|1>") split into the feed of each planned path, and the
// plan's program.json and print.json read directly (not through the code that wrote them).
//
// Fibre: the fibre extruder's steps between two cuts (rising edges of the cutter pin D11) are one
// fibre path: its thread (print.json board.thread_feed_mm) plus what fibre_start meters up to the
// cut (its length_mm). PLA: each PLA path is one forward run of the PLA extruder (the prime, then
// the metered path) and one backward run (the retract); forward minus backward is
// length_mm x board.pla_e_per_path_mm of its extrude_on event.

#include <string>
#include <vector>

namespace fibrecell::tools {

struct PathFeed {
    std::string kind;       // "fibre" or "pla"
    int layer = 0, path = 0;
    double planned_mm = 0;  // filament or fibre the plan feeds for it
    double fed_mm = 0;      // what the pins show; 0 when the pins show no such path
    double error() const { return planned_mm > 0 ? (fed_mm - planned_mm) / planned_mm : 0; }
};

struct BoardCheck {
    std::vector<PathFeed> paths;   // in print order, fibre and PLA each
    int planned_fibre_paths = 0, fibre_runs = 0;  // fibre_runs: feed segments the pins show
    int planned_pla_paths = 0, pla_runs = 0;
    int planned_cuts = 0, cuts = 0;
    int steps_while_disabled = 0;
    double worst_error = 0;        // largest |fed - planned| / planned
    std::vector<std::string> problems;  // empty: the board did what was planned within tolerance
};

struct BoardCheckOptions {
    double steps_per_mm = 105;
    bool invert_e_dir = false;
    double tolerance = 0.005;      // relative, per path
};

// Throws std::runtime_error naming the file when a file cannot be read or is not what it should be.
// The edge log may still be growing: a last line without its newline is left out.
BoardCheck check_board(const std::string& plan_dir, const std::string& edge_log,
                       const BoardCheckOptions& o = {});

}  // namespace fibrecell::tools
