#pragma once
// Where a print re-enters after an interruption (a crash, a power loss, a fault), from the print
// program and the journal's last confirmed event. The unit of re-entry is the interrupted fibre
// path or the interrupted PLA layer: the resumed run starts at its first path's approach (after
// the service's lift, re-heat, re-thread and re-prime) and every event before its first event is
// done and never fed again.
//
//   * A fibre path counts as done once its cut is confirmed: all its fibre is fed and cut, the last
//     cutter distance is only dragged out by the motion. Interrupted between its fibre_start and
//     its cut, the fibre is still in the nozzle and bonded to the part: the resumed run cuts it
//     first (`cut_first`), and the rest of the path is laid as a new fibre from where the feed
//     the journal recorded ends (`fibre_fed_mm`, 0: from the path start). All of it fed: the
//     path is done but for that cut.
//   * A PLA layer re-enters at its first path. Its paths whose extrude_off was confirmed are done:
//     their events are listed in `done_in_unit` and must not be fed again; the path that was
//     extruding when the print stopped is extruded again from its start.
//   * Interrupted between units (a layer_end, a head_switch, a path_end not confirmed), the print
//     re-enters at the next unit; nothing is fed twice.

#include "drivers/abb/program/print_program.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace fibrecell::daemon::print {

enum class ResumeUnit { fibre_path, pla_layer };

struct ResumePoint {
    std::int64_t last_confirmed = 0;
    // Nothing left to feed: every path of the program is done (only layer ends, the final lift
    // remain). The other fields are then unset.
    bool nothing_left = false;
    ResumeUnit unit = ResumeUnit::pla_layer;
    int layer = -1;  // ToolpathLayer::index of the unit
    int path = -1;   // the fibre path, or the PLA layer's first path
    drivers::abb::Nozzle nozzle = drivers::abb::Nozzle::pla;
    std::size_t first_move = 0;    // index into program.moves: the approach onto the unit's start
    std::int64_t first_event = 0;  // the unit's first event; every one before it is done
    std::vector<std::int64_t> done_in_unit;  // events >= first_event already done (PLA paths)
    std::vector<std::int64_t> fed_again;     // confirmed events the resumed run performs again
    // Fibre path whose fibre_start was confirmed: the fibre left in the part is cut before the
    // lift; the path re-enters this far along it (feed up to the cut, as fed before) with a new
    // thread of the fibre, and only the rest is fed.
    bool cut_first = false;
    double fibre_fed_mm = 0;

    // An event that was fully done and is never fed again.
    bool done(std::int64_t sequence) const;
};

// Fibre the board took along a fibre path before the interruption (the journal's last `fed`).
struct FibreFed {
    std::int64_t sequence = 0;  // the path's fibre_start
    double mm = 0;
};

// last_confirmed: 0 (nothing done) .. program.events.size(). Throws std::invalid_argument outside.
// `fed` counts only when it names the interrupted fibre path.
ResumePoint resume_point(const drivers::abb::PrintProgram& program, std::int64_t last_confirmed,
                         std::optional<FibreFed> fed = std::nullopt);

}  // namespace fibrecell::daemon::print
