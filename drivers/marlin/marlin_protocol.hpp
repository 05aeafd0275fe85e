#pragma once
// The Marlin host protocol as a state machine with no I/O (docs/marlin-link.md, "The host
// protocol, from the firmware's side" and "What the link does"): line numbering, a bounded send
// window, the go-back-N resend engine and the per-class ok deadlines.
// The owner feeds it received lines and clock ticks and gives it a function that writes bytes;
// MarlinLink does that over a serial port, tests can do it by hand.

#include "drivers/marlin/marlin_line.hpp"
#include "drivers/marlin/marlin_reply.hpp"

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>

namespace fibrecell::drivers::marlin {

using Clock = std::chrono::steady_clock;
using Seconds = std::chrono::duration<double>;

// Whether the firmware prints `ok` after `Resend:` (current bugfix-2.1.x) or not (older builds).
enum class ResendOk { detect, always, never };

struct ProtocolSettings {
    int window_lines = 1;             // lines in flight; >1 only within BUFSIZE (4) - 1
    int window_bytes = 100;           // unacknowledged bytes, kept under the 128-byte RX ring
    Seconds ok_timeout{5.0};          // normal commands
    Seconds motion_timeout{30.0};     // G0/G1: the ok waits for a free planner block
    Seconds long_timeout{300.0};      // M400, G4, M226, G28, M3/M5 (busy lines extend it)
    Seconds heating_liveness{10.0};   // M109/M190: max gap between busy/temperature lines
    Seconds silence_timeout{30.0};    // nothing at all received while a line is in flight
    // Once the firmware has sent a busy keepalive (HOST_KEEPALIVE_FEATURE, every 2 s while a
    // command blocks), a motion or long-running line with neither its ok nor a busy line for
    // this long was lost on the wire: it is probed then, not after its class's timeout.
    Seconds keepalive_liveness{6.0};
    Seconds resend_ok_wait{0.5};      // ResendOk::detect: how long to wait for the ok
    Seconds probe_settle{0.2};        // after a timeout probe: time for a late duplicate reply
    int max_probes = 3;               // consecutive ok timeouts before the link is declared dead
    int max_consecutive_resends = 10; // the same line requested this often is a resend loop
    ResendOk resend_ok = ResendOk::detect;
};

// Why a link or a request failed; the text forms are stable (logs, job reasons).
enum class LinkFailure {
    none,
    firmware_reset,       // `start` while numbered lines were outstanding or mid-session
    firmware_halted,      // kill()/thermal runaway/stopped: the board needs a reset
    emergency_stop,       // M112 was sent
    resend_out_of_window, // the firmware asked for a line we never sent or already had acked
    resend_loop,          // the same line requested max_consecutive_resends times
    ack_timeout,          // ok never came, probes exhausted
    silent,               // nothing received for silence_timeout
    heating_stalled,      // no busy/temperature line during M109/M190 for heating_liveness
    link_lost,            // the port closed or failed (cable pull)
    aborted,              // the host discarded the request
};
std::string_view to_string(LinkFailure f);

struct ProtocolStats {
    std::uint64_t lines_sent = 0;     // including resends and probes
    std::uint64_t lines_acked = 0;
    std::uint64_t resend_requests = 0;
    std::uint64_t resends_ignored = 0;  // duplicates caused by lines already in flight
    std::uint64_t timeouts = 0;
    std::uint64_t unexpected_oks = 0;
};

class MarlinProtocol {
  public:
    struct Hooks {
        std::function<void(std::string_view bytes)> write;       // must not call back in
        std::function<void(std::int64_t line)> acked;            // a numbered line executed
        std::function<void(LinkFailure, const std::string&)> failed;
        std::function<void(const Reply&)> observed;              // every parsed line (logging)
    };

    MarlinProtocol(ProtocolSettings settings, Hooks hooks);

    // Starts a numbering session at line `first` (0 on a fresh connection): queues
    // `N<first> M110 N<first>`; no numbered line is sent before its ok.
    void begin_session(std::int64_t first, Clock::time_point now);

    // Queues one command (comments stripped, non-empty); returns its line number.
    // Throws LineError when it cannot be framed.
    std::int64_t enqueue(std::string_view command, Clock::time_point now);

    // Writes an unnumbered emergency command (M108, M112, M410) ahead of everything queued.
    void send_emergency(std::string_view command);

    // Drops queued lines that were not sent yet; returns how many. In-flight lines stay tracked.
    std::size_t discard_unsent();

    void on_line(std::string_view raw, Clock::time_point now);
    void on_tick(Clock::time_point now);
    // The port is gone: fail with link_lost.
    void on_link_lost(const std::string& detail);

    bool failed() const { return failure_ != LinkFailure::none; }
    LinkFailure failure() const { return failure_; }
    bool seen_start() const { return seen_start_; }
    bool session_synced() const { return session_synced_; }
    std::int64_t next_line() const { return next_line_; }
    std::size_t in_flight() const { return static_cast<std::size_t>(next_to_send_ - first_unacked_); }
    std::size_t queued() const { return static_cast<std::size_t>(next_line_ - first_unacked_); }
    const ProtocolStats& stats() const { return stats_; }
    std::optional<bool> resend_ok_detected() const { return resend_ok_known_; }

  private:
    struct Entry {
        std::int64_t line;
        std::string framed;            // with the trailing newline
        CommandClass cls;
        bool barrier = false;          // M110: nothing else in flight with it
        Clock::time_point deadline_base{};  // send time, moved on by liveness lines
        Clock::time_point sent_at{};
    };
    // What each `ok` in wire order pays for: a numbered line or an out-of-band command.
    struct OkOwed {
        std::int64_t line;  // -1: an out-of-band command (M108, M410)
    };

    Entry& entry(std::int64_t line) { return lines_[static_cast<std::size_t>(line - first_unacked_)]; }
    void pump(Clock::time_point now);
    void handle_ok(const Reply& r, Clock::time_point now);
    void handle_resend(std::int64_t line, Clock::time_point now);
    void ack_front(Clock::time_point now);
    void probe(Clock::time_point now);
    void fail(LinkFailure f, const std::string& detail);
    Seconds timeout_for(const Entry& e) const;

    ProtocolSettings settings_;
    Hooks hooks_;
    std::deque<Entry> lines_;            // [first_unacked_, next_line_)
    std::deque<OkOwed> oks_owed_;        // in wire order
    std::int64_t first_unacked_ = 0;
    std::int64_t next_to_send_ = 0;
    std::int64_t next_line_ = 0;

    bool session_started_ = false;
    bool session_synced_ = false;        // the M110 reset was acknowledged
    bool seen_start_ = false;

    // Resend bookkeeping.
    std::optional<bool> resend_ok_known_;     // learned or configured
    int resend_oks_pending_ = 0;              // oks still due for Resend lines
    bool awaiting_resend_ok_ = false;         // detect mode: holding sends for the first one
    Clock::time_point resend_ok_deadline_{};
    std::int64_t dedupe_line_ = -1;           // requests for this line caused by in-flight lines
    int dedupe_budget_ = 0;
    // The line error before the next request was not a sequence error (a checksum error, a
    // missing checksum): the line the firmware wants arrived damaged, so the request is new,
    // never one that lines in flight caused (Marlin 1.1.9 may have flushed those unanswered).
    bool request_is_new_ = false;
    std::int64_t last_request_ = -1;
    int same_request_count_ = 0;

    // Lost-ok recovery: the oldest in-flight line was re-sent with its own number.
    bool probing_ = false;
    std::int64_t probe_line_ = -1;
    int probes_ = 0;
    bool keepalive_seen_ = false;  // a busy line came: the firmware keeps a blocking line alive
    bool settling_ = false;                   // waiting for the probe copy's late reply
    Clock::time_point settle_deadline_{};

    Clock::time_point last_rx_{};
    LinkFailure failure_ = LinkFailure::none;
    ProtocolStats stats_;
};

}  // namespace fibrecell::drivers::marlin
