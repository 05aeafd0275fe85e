#pragma once
// The sync engine's decisions, single-threaded: the engine's worker feeds it the robot's counter
// changes, link states, temperature reports, the board's replies, pause and resume, and asks it to
// meter. It sends board commands (MarlinLink::submit, replies handed to a watcher), writes barrier
// releases and pause requests (RobotIoLink), and keeps what status() shows. docs/sync-engine.md.

#include "daemon/sync/board_feed_queue.hpp"
#include "daemon/sync/event_counter.hpp"
#include "daemon/sync/feed_meter.hpp"
#include "daemon/sync/latency_stats.hpp"
#include "daemon/sync/sync_options.hpp"
#include "daemon/sync/sync_status.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "drivers/extruder/extruder_controller.hpp"
#include "drivers/marlin/marlin_link.hpp"

#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fibrecell::daemon::sync {

struct SyncDevices {
    const drivers::abb::PrintProgram& program;
    drivers::ExtruderController& extruder;
    drivers::marlin::MarlinLink& board;
    drivers::abb::RobotIoLink& robot;
};

struct SyncObservers {
    std::function<void(const EventDone&)> event_done;
    std::function<void(const std::string& reason)> fault;
    std::function<void(const SyncProgress&)> progress;
};

class EventProcessor {
  public:
    // Takes each submitted request's reply future with the ticket it was given.
    using ReplySink = std::function<void(std::uint64_t ticket, std::future<drivers::marlin::CommandOutcome>)>;

    EventProcessor(SyncDevices devices, const SyncOptions& options, const SyncObservers& observers,
                   ReplySink replies, EventTimings& timings);

    // Puts the board in relative E with both hotend targets set; faults when a link is down.
    void begin();

    void counter_changed(const drivers::abb::EventCounterChange& change);
    void robot_link_state(const drivers::abb::RobotIoStateChange& change);
    void temperature(const drivers::marlin::TemperatureReport& report);
    void board_reply(std::uint64_t ticket, const drivers::marlin::CommandOutcome& outcome,
                     SteadyClock::time_point at);
    void pause(SteadyClock::time_point now);
    void resume(SteadyClock::time_point now);
    // Sends the metering pieces due at `now`.
    void meter(SteadyClock::time_point now);
    // Stops metering, aborts the board's queue, asks the robot to stop; the first reason stays.
    void fault(const std::string& reason);

    // When meter() has something to send next (empty: nothing scheduled).
    std::optional<SteadyClock::time_point> next_wakeup() const;
    SyncStatus status() const;  // without the timing summaries (EventTimings has them)

  private:
    // An event received and not yet confirmed: done once the reply for `ticket` is in.
    struct Unconfirmed {
        std::int64_t sequence;
        std::uint64_t ticket;  // its last request, or the latest one before it (none: 0)
    };
    // The first command of an event: its reply time is the event's ok latency.
    struct OkProbe {
        drivers::abb::EventKind kind;
        SteadyClock::time_point first_read;
    };
    struct MeteredPath {
        const drivers::abb::ProgramEvent* event;
        FeedMeter meter;
        double e_per_path_mm;  // 1 for fibre; the PLA line's ratio
        struct Sent {
            double e_mm;
            double run_s;  // real seconds the board takes to feed it (its path time)
        };
        std::map<std::uint64_t, Sent> in_flight;  // piece tickets, until answered
        double e_fed_mm = 0;                      // pieces answered ok
        BoardFeedQueue board;                     // answered, maybe not run yet
    };

    const drivers::abb::ProgramEvent& event(std::int64_t sequence) const;
    void process(std::int64_t sequence, const drivers::abb::EventCounterChange& change);
    std::vector<std::string> commands_for(const drivers::abb::ProgramEvent& e);
    bool hotend_ready(drivers::Head head) const;
    std::uint64_t send(const std::vector<std::string>& lines);
    std::uint64_t send_for_event(const drivers::abb::ProgramEvent& e,
                                 const drivers::abb::EventCounterChange& change,
                                 const std::vector<std::string>& lines);
    void confirm_ready();
    void confirm(std::int64_t sequence);
    void release(std::int64_t sequence);
    void start_metering(const drivers::abb::ProgramEvent& e, SteadyClock::time_point robot_start);
    void stop_metering();
    void record_shortfall(ShortfallKind kind, const drivers::abb::ProgramEvent& e, double mm);
    void piece_answered(std::uint64_t ticket, const drivers::marlin::CommandOutcome& outcome,
                        SteadyClock::time_point at);
    std::string take_back_unrun_feed(SteadyClock::time_point reset_at);
    std::string where() const;

    SyncDevices dev_;
    SyncOptions options_;
    const SyncObservers& observers_;
    ReplySink replies_;
    EventTimings& timings_;
    double pla_e_per_path_mm_;

    EventCounter counter_;
    std::int64_t last_confirmed_;
    std::deque<Unconfirmed> unconfirmed_;
    std::map<std::uint64_t, OkProbe> ok_probes_;
    std::uint64_t last_ticket_ = 0, acked_ticket_ = 0;
    std::optional<std::int64_t> unreleased_barrier_;  // received, release not written yet
    std::optional<std::int64_t> held_barrier_;        // confirmed while paused
    std::optional<MeteredPath> metering_;  // kept (stopped) when a fault interrupts it
    bool paused_ = false;
    bool faulted_ = false;
    std::string fault_reason_;
    std::optional<double> pla_hotend_c_, ccf_hotend_c_;
    SyncStats stats_;
};

}  // namespace fibrecell::daemon::sync
