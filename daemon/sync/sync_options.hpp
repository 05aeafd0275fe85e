#pragma once
// Settings of one print's sync engine: where the run starts, the job's temperatures and PLA line
// (to meter extrude_pla), the head-switch temperature check, and the metering pace.

#include "daemon/sync/latency_stats.hpp"
#include "drivers/extruder/extruder_controller.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace fibrecell::daemon::sync {

// A path whose metering a fault interrupted: the new engine meters the rest of it first.
// With `rethread` (a re-entry in the middle of a fibre path after a restart), `sequence` is the
// run's first event, a fibre_start done again: the fibre is threaded anew and, once the robot
// leaves that barrier, only the feed after `e_fed_mm` is metered.
struct ResumeFeed {
    std::int64_t sequence = 0;  // its fibre_start or extrude_on event (before first_event)
    double e_fed_mm = 0;        // feed the board took before the fault (MeteringStatus::e_fed_mm)
    bool rethread = false;
};

struct SyncOptions {
    std::int64_t first_event = 1;      // resume: every event before this one is done
    std::optional<ResumeFeed> resume_feed;
    // Resume: events at or after first_event whose work was done before an interruption (the PLA
    // paths of a re-entered layer): the robot passes them again, the board gets nothing.
    std::vector<std::int64_t> skip_events;
    drivers::HotendTargets hotends;    // job process.*.nozzle_temp_c
    double pla_line_width_mm = 0.8;    // job process.pla.line_width_mm
    double pla_layer_height_mm = 0.8;  // job layers.pla_layer_height_mm
    double temp_window_c = 5;          // head switch: M109 unless the hotend reads this close
    double fibre_piece_mm = 1;         // path covered by one metered fibre G1 E
    double pla_piece_mm = 2;           // path covered by one metered PLA G1 E
    double lead_s = 0.3;               // metered feed sent ahead of the robot [s of path]
    // The lead is at least this much real time (only a high time scale makes it longer): the
    // host's latencies (the robot I/O poll every 2 ms, a serial round trip) are real milliseconds,
    // which at the demo's 120x were more than the 2.5 ms that 0.3 s of path came to, and
    // paths ended with feed still unsent (4-5 of the Loop's per run).
    double min_lead_real_s = 0.02;
    double time_scale = 1;             // simulated seconds per real second (simulated cell)
    std::size_t timing_window = 4096;  // latency samples kept per kind for median and p99
    // The print's latency samples, shared by the engines of one print (a resume after a device
    // fault runs a new engine; result.json counts the whole print). Null: the engine's own.
    std::shared_ptr<EventTimings> timings;
    // Shortfalls (SyncStats::shortfalls): metered feed dropped at a path's end above
    // shortfall_mm (less is within one re-prime), a cut that came late_cut_mm or more after the
    // robot passed its place.
    double shortfall_mm = 0.05;
    double late_cut_mm = 2.0;
    // Hotend readings known at the start (a pre-flight M109 just brought both to temperature),
    // until the board's own reports come; none: a head switch waits for a report or heats.
    std::optional<double> pla_hotend_c, ccf_hotend_c;
};

// The lead the meter paces with [s of path]: lead_s, or min_lead_real_s of real time when that
// is longer (a simulated cell at a high time scale).
double effective_lead_s(const SyncOptions& options);

// Throws std::invalid_argument naming the field: non-positive sizes, speeds or windows,
// a negative lead, first_event outside 1..events_total + 1, a resume_feed that does not name a
// fibre_start or extrude_on event before first_event (a rethread: first_event itself) or feeds a
// negative amount.
void validate(const SyncOptions& options, std::int64_t events_total);

}  // namespace fibrecell::daemon::sync
