#pragma once
// What the sync engine tells the service: the observers' payloads and status() with its
// statistics. Sequence numbers are full event numbers (1-based, not wrapped).

#include "daemon/sync/latency_stats.hpp"
#include "drivers/abb/program/print_program.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::sync {

// An event whose board commands were all acknowledged (the service journals it).
struct EventDone {
    std::int64_t sequence = 0;
    drivers::abb::EventKind kind = drivers::abb::EventKind::layer_end;
    int layer = -1;
    int path = -1;
    bool released = false;  // a barrier whose release was written (false: held by a pause)
};

// After each layer_end: how far the print is.
struct SyncProgress {
    int layer = -1;                   // the layer just finished (ToolpathLayer::index)
    std::int64_t events_done = 0;     // the last confirmed sequence
    std::int64_t events_total = 0;
};

// The path being metered, if any; after a fault, the path whose metering it interrupted
// (active false): e_fed_mm is what a new engine continues after (SyncOptions::resume_feed).
struct MeteringStatus {
    bool active = false;
    std::int64_t sequence = 0;  // the fibre_start or extrude_on event that started it
    std::size_t pieces_sent = 0, pieces_total = 0;
    double e_sent_mm = 0, e_total_mm = 0;
    double e_fed_mm = 0;  // pieces the board took (answered ok; an aborted one was never fed)
    std::size_t pieces_unanswered = 0;  // sent, reply not in yet (e_fed_mm may still grow)
};

// Something a path did not get as planned: the part on the bed differs from the plan there.
enum class ShortfallKind {
    fibre_feed_dropped,  // metered fibre still unsent when the cut came
    pla_feed_dropped,    // metered PLA still unsent when extrude_off came
    late_cut,            // the robot had run on past the cut's place when the cutter got it
};
std::string_view to_string(ShortfallKind k);

struct Shortfall {
    ShortfallKind kind = ShortfallKind::fibre_feed_dropped;
    std::int64_t sequence = 0;  // the path's fibre_start / extrude_on, or the cut event
    int layer = 0, path = 0;    // of that event (ProgramEvent::layer, path)
    double mm = 0;              // feed not laid, or how far past its place the cut came
};

// Kept per engine; a print keeps at most this many (the counts in SyncStats go on).
inline constexpr std::size_t max_shortfalls = 1000;

struct SyncStats {
    std::uint64_t events_done = 0;
    std::uint64_t gaps = 0;           // counter jumps of more than one event
    std::uint64_t events_caught_up = 0;  // events processed because of a gap
    std::uint64_t duplicates = 0;     // counter values already seen
    std::uint64_t events_skipped = 0;  // SyncOptions::skip_events passed without commands
    std::uint64_t counter_resets = 0; // 0 from the robot's run request before any event
    std::uint64_t heat_waits = 0;     // M109 sent at a head switch
    std::uint64_t paths_completed = 0;  // path_end events
    std::uint64_t pieces_sent = 0;    // metering pieces over all paths
    // Metered feed still unsent when the cut came (fibre) or extrude_off came (PLA): dropped.
    std::uint64_t feed_left_at_cut = 0;
    double feed_left_at_cut_mm = 0;
    std::uint64_t extrusion_left_at_off = 0;
    double extrusion_left_at_off_mm = 0;
    // Feed the board acknowledged but, by its feed rate, had not run when its MCU was reset: lost
    // with its planner, taken off the path's fed amount (a resume feeds it again).
    double feed_lost_in_reset_mm = 0;
    std::vector<KindTiming> timing;   // per event kind with board commands
    std::uint64_t late_cuts = 0;      // cuts at least SyncOptions::late_cut_mm late
    std::vector<Shortfall> shortfalls;  // in event order, at most max_shortfalls
};

struct SyncStatus {
    bool running = false;                  // started and not stopped
    std::int64_t last_received = 0;        // the latest event taken from the robot's counter
    std::int64_t last_confirmed = 0;       // the latest event done (resume after it)
    std::int64_t pending = 0;              // received, not confirmed yet
    std::int64_t events_total = 0;
    bool finished = false;                 // the program's last event is confirmed
    bool paused = false;
    std::optional<std::int64_t> held_barrier;  // a barrier done but held by the pause
    bool faulted = false;
    std::string fault_reason;
    std::optional<double> pla_hotend_c, ccf_hotend_c;  // latest board reports
    MeteringStatus metering;
    SyncStats stats;
};

}  // namespace fibrecell::daemon::sync
