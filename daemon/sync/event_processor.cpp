#include "daemon/sync/event_processor.hpp"

#include "daemon/sync/board_commands.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace fibrecell::daemon::sync {

using drivers::Head;
using drivers::abb::EventCounterChange;
using drivers::abb::EventKind;
using drivers::abb::ProgramEvent;
using drivers::marlin::CommandOutcome;

namespace {

Head head_of(const ProgramEvent& e) {
    return e.nozzle == drivers::abb::Nozzle::pla ? Head::pla : Head::ccf;
}

double ms_between(SteadyClock::time_point from, SteadyClock::time_point to) {
    return std::chrono::duration<double, std::milli>(to - from).count();
}

std::string describe(const ProgramEvent& e) {
    return "event " + std::to_string(e.sequence) + " (" + std::string(to_string(e.kind)) + ")";
}

}  // namespace

EventProcessor::EventProcessor(SyncDevices devices, const SyncOptions& options,
                               const SyncObservers& observers, ReplySink replies,
                               EventTimings& timings)
    : dev_(devices),
      options_(options),
      observers_(observers),
      replies_(std::move(replies)),
      timings_(timings),
      pla_e_per_path_mm_(pla_e_per_path_mm(dev_.extruder.config(), options.pla_line_width_mm,
                                           options.pla_layer_height_mm)),
      counter_(options.first_event - 1),
      last_confirmed_(options.first_event - 1),
      pla_hotend_c_(options.pla_hotend_c),
      ccf_hotend_c_(options.ccf_hotend_c) {}

const ProgramEvent& EventProcessor::event(std::int64_t sequence) const {
    return dev_.program.events[static_cast<std::size_t>(sequence - 1)];
}

void EventProcessor::begin() {
    using drivers::DeviceState;
    if (dev_.board.state() != DeviceState::active)
        return fault("extruder board: the link is " + std::string(to_string(dev_.board.state())) +
                     ", not active");
    if (dev_.robot.state() == drivers::abb::RobotIoState::fault)
        return fault("robot I/O: " + dev_.robot.snapshot().fault_reason);
    send(dev_.extruder.prepare(options_.hotends, false));
    spdlog::info("sync.started first_event={} events={}", options_.first_event,
                 dev_.program.events.size());
    if (const auto& r = options_.resume_feed; r && !r->rethread) {
        // The path a fault interrupted: the robot goes on from about where the fed feed ends.
        const ProgramEvent& e = event(r->sequence);
        if (e.kind != EventKind::fibre_start && e.kind != EventKind::extrude_on)
            return fault("resume: " + describe(e) + " does not start a metered path");
        const auto now = SteadyClock::now();
        start_metering(e, now);
        try {
            metering_->meter.skip_fed(r->e_fed_mm, now);
        } catch (const std::invalid_argument& x) {
            return fault("resume: " + describe(e) + ": " + x.what());
        }
        metering_->e_fed_mm = r->e_fed_mm;
        spdlog::info("sync.resume_feed {} fed={:.5f} of {:.5f} mm", describe(e), r->e_fed_mm,
                     metering_->meter.e_total_mm());
    }
}

// --- Robot side ---------------------------------------------------------------------------------

void EventProcessor::counter_changed(const EventCounterChange& change) {
    if (faulted_) return;
    const CounterAdvance a = counter_.advance(change.value);
    switch (a.step) {
        case CounterStep::duplicate: ++stats_.duplicates; return;
        case CounterStep::reset: ++stats_.counter_resets; return;
        case CounterStep::backwards:
            return fault("robot event counter went back from event " + std::to_string(a.from) +
                         " to " + std::to_string(a.to) + " (raw " + std::to_string(change.value) + ")");
        case CounterStep::forward: break;
    }
    const auto total = static_cast<std::int64_t>(dev_.program.events.size());
    if (a.to > total)
        return fault("robot event counter reached event " + std::to_string(a.to) +
                     " beyond the program's last event " + std::to_string(total));
    if (a.to - a.from > 1) {
        ++stats_.gaps;
        stats_.events_caught_up += static_cast<std::uint64_t>(a.to - a.from - 1);
        spdlog::warn("sync.gap from={} to={}: catching up", a.from, a.to);
    }
    for (std::int64_t s = a.from + 1; s <= a.to && !faulted_; ++s) process(s, change);
}

void EventProcessor::robot_link_state(const drivers::abb::RobotIoStateChange& change) {
    if (change.to == drivers::abb::RobotIoState::fault) fault("robot I/O: " + change.reason);
}

void EventProcessor::process(std::int64_t sequence, const EventCounterChange& change) {
    const ProgramEvent& e = event(sequence);
    // The robot cannot pass a barrier before its release: if it did, the programs disagree.
    if (unreleased_barrier_)
        return fault("robot reported " + describe(e) + " before barrier " +
                     std::to_string(*unreleased_barrier_) + " was released");
    if (std::binary_search(options_.skip_events.begin(), options_.skip_events.end(), sequence)) {
        // Done before an interruption: confirmed (and released) without a board command.
        ++stats_.events_skipped;
        if (e.barrier) unreleased_barrier_ = sequence;
        unconfirmed_.push_back({sequence, last_ticket_});
        confirm_ready();
        return;
    }
    const std::uint64_t ticket = send_for_event(e, change, commands_for(e));
    if (e.kind == EventKind::extrude_on) start_metering(e, change.first_read);
    if (e.barrier) unreleased_barrier_ = sequence;
    unconfirmed_.push_back({sequence, ticket});
    confirm_ready();
}

std::vector<std::string> EventProcessor::commands_for(const ProgramEvent& e) {
    drivers::ExtruderController& x = dev_.extruder;
    std::vector<std::string> lines;
    switch (e.kind) {
        case EventKind::head_switch:
            lines = x.select(head_of(e));
            if (!hotend_ready(head_of(e))) {
                lines.push_back(heat_and_wait(x.config(), head_of(e), options_.hotends.of(head_of(e))));
                ++stats_.heat_waits;
            }
            break;
        case EventKind::fibre_start:
            stop_metering();
            lines = x.thread_fibre();
            lines.push_back(wait_for_moves());  // release once the fibre is at the nozzle tip
            break;
        case EventKind::cut:
            stop_metering();
            lines = x.cut();
            break;
        case EventKind::extrude_on:
            stop_metering();
            lines = x.prime();
            break;
        case EventKind::extrude_off:
            stop_metering();
            lines = x.retract();
            break;
        case EventKind::path_end: ++stats_.paths_completed; break;
        case EventKind::layer_end: break;
    }
    return lines;
}

bool EventProcessor::hotend_ready(Head head) const {
    const auto& reading = head == Head::pla ? pla_hotend_c_ : ccf_hotend_c_;
    return reading && std::abs(*reading - options_.hotends.of(head)) <= options_.temp_window_c;
}

// --- Board side ---------------------------------------------------------------------------------

void EventProcessor::temperature(const drivers::marlin::TemperatureReport& report) {
    const drivers::ExtruderConfig& c = dev_.extruder.config();
    if (const auto* r = report.find("T" + std::to_string(c.pla_tool))) pla_hotend_c_ = r->actual_c;
    if (const auto* r = report.find("T" + std::to_string(c.ccf_tool))) ccf_hotend_c_ = r->actual_c;
}

std::uint64_t EventProcessor::send(const std::vector<std::string>& lines) {
    const std::uint64_t ticket = ++last_ticket_;
    replies_(ticket, dev_.board.submit(lines));
    return ticket;
}

// The first line goes alone so that its reply times the event; returns the last ticket (the
// latest one before the event when it has no commands).
std::uint64_t EventProcessor::send_for_event(const ProgramEvent& e, const EventCounterChange& change,
                                             const std::vector<std::string>& lines) {
    if (lines.empty()) return last_ticket_;
    const auto submitted = SteadyClock::now();
    const std::uint64_t first = send({lines.front()});
    // A barrier's robot stands still; elsewhere it ran on at the path speed meanwhile.
    const double ran_s = ms_between(change.first_read, submitted) / 1000.0 * options_.time_scale;
    const double ran_mm = e.barrier ? 0.0 : e.speed_mm_s * ran_s;
    timings_.record_submit(e.kind, ms_between(change.first_read, submitted), ran_mm);
    if (e.kind == EventKind::cut && ran_mm >= options_.late_cut_mm) {
        ++stats_.late_cuts;
        record_shortfall(ShortfallKind::late_cut, e, ran_mm);
        spdlog::warn("sync.late_cut {} {:.3f} mm past its place", describe(e), ran_mm);
    }
    ok_probes_[first] = {e.kind, change.first_read};
    if (lines.size() == 1) return first;
    return send({lines.begin() + 1, lines.end()});
}

void EventProcessor::board_reply(std::uint64_t ticket, const CommandOutcome& outcome,
                                 SteadyClock::time_point at) {
    piece_answered(ticket, outcome, at);  // also after a fault: what the board took is fed
    if (faulted_) return;
    if (!outcome.ok()) {
        // A request sent after the link failed only says "not active": name the link's cause.
        const bool link_failed = dev_.board.fault() != drivers::marlin::LinkFailure::none;
        const auto failure = link_failed ? dev_.board.fault() : outcome.failure;
        const std::string detail = link_failed ? dev_.board.fault_detail() : outcome.detail;
        std::string lost;
        if (failure == drivers::marlin::LinkFailure::firmware_reset)
            lost = take_back_unrun_feed(dev_.board.fault_time().value_or(at));
        return fault("extruder board: " + std::string(to_string(failure)) + ": " + detail + where() +
                     lost);
    }
    acked_ticket_ = ticket;
    if (const auto probe = ok_probes_.find(ticket); probe != ok_probes_.end()) {
        timings_.record_ok(probe->second.kind, ms_between(probe->second.first_read, at));
        ok_probes_.erase(probe);
    }
    confirm_ready();
}

// --- Confirmation and barriers ------------------------------------------------------------------

void EventProcessor::confirm_ready() {
    while (!faulted_ && !unconfirmed_.empty() && unconfirmed_.front().ticket <= acked_ticket_) {
        const std::int64_t s = unconfirmed_.front().sequence;
        unconfirmed_.pop_front();
        confirm(s);
    }
}

void EventProcessor::confirm(std::int64_t sequence) {
    const ProgramEvent& e = event(sequence);
    last_confirmed_ = sequence;
    ++stats_.events_done;
    if (e.barrier) {
        if (paused_)
            held_barrier_ = sequence;  // released by resume()
        else
            release(sequence);
    }
    if (observers_.event_done)
        observers_.event_done({sequence, e.kind, e.layer, e.path, e.barrier && !paused_});
    if (e.kind == EventKind::layer_end && observers_.progress)
        observers_.progress({e.layer, sequence, static_cast<std::int64_t>(dev_.program.events.size())});
}

void EventProcessor::release(std::int64_t sequence) {
    dev_.robot.set_release(static_cast<std::uint16_t>(sequence & 0xFFFF));
    unreleased_barrier_.reset();
    held_barrier_.reset();
    const ProgramEvent& e = event(sequence);
    // The robot leaves the barrier now: the fibre feed is paced from here.
    if (e.kind != EventKind::fibre_start) return;
    const auto now = SteadyClock::now();
    start_metering(e, now);
    const auto& r = options_.resume_feed;
    if (!r || !r->rethread || r->sequence != sequence) return;
    // Re-entered where the feed before the interruption ended: only the rest is fed.
    try {
        metering_->meter.skip_fed(r->e_fed_mm, now);
    } catch (const std::invalid_argument& x) {
        return fault("resume: " + describe(e) + ": " + x.what());
    }
    metering_->e_fed_mm = r->e_fed_mm;
    spdlog::info("sync.resume_feed {} rethreaded, fed={:.5f} of {:.5f} mm", describe(e),
                 r->e_fed_mm, metering_->meter.e_total_mm());
}

// --- Metering -----------------------------------------------------------------------------------

void EventProcessor::start_metering(const ProgramEvent& e, SteadyClock::time_point robot_start) {
    const bool fibre = e.kind == EventKind::fibre_start;
    const double ratio = fibre ? 1.0 : pla_e_per_path_mm_;
    auto pieces = split_feed(e.length_mm, e.length_mm * ratio,
                             fibre ? options_.fibre_piece_mm : options_.pla_piece_mm);
    const MeterPacing pacing{e.speed_mm_s, effective_lead_s(options_), options_.time_scale};
    metering_.emplace(MeteredPath{&e, FeedMeter(std::move(pieces), pacing, robot_start), ratio});
    if (paused_) metering_->meter.pause(SteadyClock::now());
}

void EventProcessor::meter(SteadyClock::time_point now) {
    if (faulted_ || !metering_) return;
    const ProgramEvent& e = *metering_->event;
    drivers::ExtruderController& x = dev_.extruder;
    for (const MeterPiece& p : metering_->meter.take_due(now)) {
        const std::uint64_t ticket =
            e.kind == EventKind::fibre_start
                ? send(x.feed_fibre(p.e_mm, e.speed_mm_s))
                // the path share that extrude_pla turns back into exactly p.e_mm
                : send(x.extrude_pla(p.e_mm / metering_->e_per_path_mm, e.speed_mm_s,
                                     options_.pla_line_width_mm, options_.pla_layer_height_mm));
        const double path_mm = p.e_mm / metering_->e_per_path_mm;
        metering_->in_flight[ticket] = {p.e_mm, path_mm / e.speed_mm_s / options_.time_scale};
        ++stats_.pieces_sent;
    }
}

void EventProcessor::piece_answered(std::uint64_t ticket, const CommandOutcome& outcome,
                                    SteadyClock::time_point at) {
    if (!metering_) return;
    const auto piece = metering_->in_flight.find(ticket);
    if (piece == metering_->in_flight.end()) return;
    if (outcome.ok()) {
        metering_->e_fed_mm += piece->second.e_mm;
        metering_->board.acknowledged(piece->second.e_mm, piece->second.run_s, at);
    }
    metering_->in_flight.erase(piece);
}

// An MCU reset lost the moves the board had planned: what it acknowledged of the path and had
// not run by then is taken off the fed amount, so a resume feeds it again. Returns the note for
// the fault's reason.
std::string EventProcessor::take_back_unrun_feed(SteadyClock::time_point reset_at) {
    if (!metering_) return "";
    const double unrun = std::min(metering_->board.unrun_at(reset_at), metering_->e_fed_mm);
    if (unrun < 1e-5) return "";
    metering_->e_fed_mm -= unrun;
    stats_.feed_lost_in_reset_mm += unrun;
    spdlog::warn("sync.feed_lost_in_reset {} {:.5f} mm acknowledged, not run; fed={:.5f} mm",
                 describe(*metering_->event), unrun, metering_->e_fed_mm);
    return fmt::format("; {:.2f} mm of its feed the board had taken but not run is fed again on "
                       "resume",
                       unrun);
}

// Drops what was not sent yet, counted against the path kind it belonged to.
void EventProcessor::stop_metering() {
    if (!metering_) return;
    const double left = metering_->meter.e_left_mm();
    if (left > 0) {
        const bool fibre = metering_->event->kind == EventKind::fibre_start;
        (fibre ? stats_.feed_left_at_cut : stats_.extrusion_left_at_off) += 1;
        (fibre ? stats_.feed_left_at_cut_mm : stats_.extrusion_left_at_off_mm) += left;
        spdlog::warn("sync.feed_dropped {} left={:.5f} mm", describe(*metering_->event), left);
        if (left > options_.shortfall_mm)
            record_shortfall(fibre ? ShortfallKind::fibre_feed_dropped
                                   : ShortfallKind::pla_feed_dropped,
                             *metering_->event, left);
    }
    metering_.reset();
}

void EventProcessor::record_shortfall(ShortfallKind kind, const ProgramEvent& e, double mm) {
    if (stats_.shortfalls.size() < max_shortfalls)
        stats_.shortfalls.push_back({kind, e.sequence, e.layer, e.path, mm});
}

// --- Pause, resume, faults ----------------------------------------------------------------------

void EventProcessor::pause(SteadyClock::time_point now) {
    if (paused_) return;
    paused_ = true;
    dev_.robot.set_pause(true);
    if (metering_) metering_->meter.pause(now);
}

void EventProcessor::resume(SteadyClock::time_point now) {
    if (!paused_ || faulted_) return;
    paused_ = false;
    dev_.robot.set_pause(false);
    if (metering_) metering_->meter.resume(now);
    if (held_barrier_) release(*held_barrier_);
}

void EventProcessor::fault(const std::string& reason) {
    if (faulted_) return;
    faulted_ = true;
    fault_reason_ = reason;
    // Metering stops; the path stays for status(): its fed amount is where a resume goes on.
    spdlog::error("sync.fault {} last_confirmed={}", reason, last_confirmed_);
    dev_.board.abort();
    dev_.robot.set_pause(true);
    if (observers_.fault) observers_.fault(reason);
}

std::string EventProcessor::where() const {
    if (!unconfirmed_.empty()) return "; at " + describe(event(unconfirmed_.front().sequence));
    if (metering_) return "; while metering " + describe(*metering_->event);
    return "";
}

// --- Status -------------------------------------------------------------------------------------

std::optional<SteadyClock::time_point> EventProcessor::next_wakeup() const {
    if (faulted_ || !metering_) return std::nullopt;
    return metering_->meter.next_due();
}

SyncStatus EventProcessor::status() const {
    SyncStatus s;
    s.last_received = counter_.last();
    s.last_confirmed = last_confirmed_;
    s.pending = s.last_received - s.last_confirmed;
    s.events_total = static_cast<std::int64_t>(dev_.program.events.size());
    s.finished = last_confirmed_ == s.events_total;
    s.paused = paused_;
    s.held_barrier = held_barrier_;
    s.faulted = faulted_;
    s.fault_reason = fault_reason_;
    s.pla_hotend_c = pla_hotend_c_;
    s.ccf_hotend_c = ccf_hotend_c_;
    if (metering_) {
        const FeedMeter& m = metering_->meter;
        s.metering = {!faulted_,   metering_->event->sequence, m.sent(), m.total(), m.e_sent_mm(),
                      m.e_total_mm(), metering_->e_fed_mm, metering_->in_flight.size()};
    }
    s.stats = stats_;
    return s;
}

}  // namespace fibrecell::daemon::sync
