#include "daemon/print/print_session.hpp"

#include "drivers/abb/rapid/reader.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"

#include <thread>

namespace fibrecell::daemon::print {

namespace abb = drivers::abb;
using Clock = std::chrono::steady_clock;

std::string_view to_string(PrintPhase p) {
    switch (p) {
        case PrintPhase::idle: return "idle";
        case PrintPhase::printing: return "printing";
        case PrintPhase::paused: return "paused";
        case PrintPhase::completed: return "completed";
        case PrintPhase::aborted: return "aborted";
        case PrintPhase::faulted: return "faulted";
    }
    return "unknown";
}

namespace {

bool finished(PrintPhase p) {
    return p == PrintPhase::completed || p == PrintPhase::aborted || p == PrintPhase::faulted;
}

// Waits for a board request; a failure names the step.
void await_board(std::future<drivers::marlin::CommandOutcome> f, std::chrono::milliseconds timeout,
                 const std::string& step) {
    if (f.wait_for(timeout) != std::future_status::ready)
        throw PrintError(step + ": no answer from the extruder board within " +
                         std::to_string(timeout.count() / 1000) + " s");
    const auto outcome = f.get();
    if (!outcome.ok()) throw PrintError(step + ": " + outcome.detail);
}

}  // namespace

PrintSession::PrintSession(const abb::PrintProgram& program, std::vector<abb::ChunkFile> chunks,
                           PrintLinks links, PrintOptions options)
    : program_(program),
      chunks_(std::move(chunks)),
      links_(links),
      options_(std::move(options)),
      fc_(links.rws) {}

PrintSession::~PrintSession() {
    std::unique_ptr<sync::SyncEngine> engine;
    {
        std::lock_guard lock(mu_);
        engine = std::move(engine_);
    }
    if (engine) engine->stop();
}

void PrintSession::robot_event(const abb::EventCounterChange& change) {
    std::lock_guard lock(mu_);
    if (engine_) engine_->robot_event(change);
}

void PrintSession::robot_link_state(const abb::RobotIoStateChange& change) {
    std::lock_guard lock(mu_);
    if (engine_) engine_->robot_link_state(change);
}

void PrintSession::board_temperature(const drivers::marlin::TemperatureReport& report) {
    std::lock_guard lock(mu_);
    if (engine_) engine_->board_temperature(report);
}

void PrintSession::on_event_done(std::function<void(const sync::EventDone&)> f) {
    on_done_ = std::move(f);
}

// A chunk that does not build would stop RAPID in the middle of the print (FcMain's WaitLoad);
// the reader finds it before anything moves.
void PrintSession::check_chunks() const {
    for (const abb::ChunkFile& c : chunks_) {
        abb::rapid::ValidateOptions o;
        o.file_name = c.file_name;
        o.known_signals = options_.signals;
        o.external_routines = {std::string(abb::barrier_routine)};
        o.max_lines = options_.max_chunk_lines;
        const auto result = abb::rapid::check_module(c.text, o);
        for (const auto& d : result.diagnostics)
            if (d.severity == abb::rapid::Severity::error)
                throw PrintError("pre-flight: " + abb::rapid::format(d));
        if (!result.module) throw PrintError("pre-flight: " + c.file_name + " cannot be read");
    }
}

void PrintSession::start() {
    check_chunks();
    if (!links_.robot_io.wait_until_up(options_.link_timeout)) {
        const auto snap = links_.robot_io.snapshot();
        throw PrintError("pre-flight: the robot I/O link is not up (" +
                         std::string(abb::to_string(snap.state)) + ": " +
                         (snap.fault_reason.empty() ? snap.last_error : snap.fault_reason) + ")");
    }
    if (links_.board.state() != drivers::DeviceState::active)
        throw PrintError("pre-flight: the extruder board is not connected (" +
                         std::string(drivers::to_string(links_.board.state())) + ")");
    try {
        fc_.ensure_running();
        wait_for_robot_heartbeat();
        end_previous_run();
        reset_service_outputs();
        fc_.upload_chunks(options_.job_dir, chunks_);
    } catch (const std::exception& e) {
        throw PrintError(std::string("pre-flight: robot program: ") + e.what());
    }
    if (options_.heat_before_start) {
        // Both targets first, then the waits: the hotends heat together.
        const drivers::HotendTargets& targets = options_.sync.hotends;
        await_board(links_.board.submit(links_.extruder.prepare(targets, false)),
                    options_.heat_timeout, "pre-flight: heat-up");
        await_board(links_.board.submit(links_.extruder.prepare(targets, true)),
                    options_.heat_timeout, "pre-flight: heat-up");
        // M109 returned: both are at temperature, whether or not a report came meanwhile.
        options_.sync.pla_hotend_c = targets.pla_c;
        options_.sync.ccf_hotend_c = targets.ccf_c;
    }
    if (options_.resume_tool)
        await_board(links_.board.submit(links_.extruder.select(*options_.resume_tool)),
                    options_.heat_timeout, "re-entry: tool select");
    if (options_.cut_before_start)
        await_board(links_.board.submit(links_.extruder.cut()), options_.heat_timeout,
                    "re-entry: cut of the interrupted fibre");
    start_engine(options_.sync.first_event, options_.sync.resume_feed);
    const int chunk_count = options_.chunk_count > 0
                                ? options_.chunk_count
                                : options_.first_chunk - 1 + static_cast<int>(chunks_.size());
    try {
        fc_.request_run({.job_dir = options_.job_dir,
                         .chunk_count = chunk_count,
                         .first_chunk = options_.first_chunk,
                         .heartbeat_timeout_s = options_.heartbeat_timeout_s},
                        options_.run_request_timeout);
    } catch (const std::exception& e) {
        std::unique_ptr<sync::SyncEngine> engine;
        {
            std::lock_guard lock(mu_);
            engine = std::move(engine_);
        }
        engine->stop();
        throw PrintError(std::string("start: ") + e.what());
    }
    std::lock_guard lock(mu_);
    status_.phase = PrintPhase::printing;
}

void PrintSession::start_engine(std::int64_t first_event,
                                std::optional<sync::ResumeFeed> resume_feed, bool paused) {
    sync::SyncOptions o = options_.sync;
    o.first_event = first_event;
    o.resume_feed = resume_feed;
    o.timings = timings_;  // one print, one set of figures, whatever the engines
    auto engine = std::make_unique<sync::SyncEngine>(program_, links_.extruder, links_.board,
                                                     links_.robot_io, o);
    if (on_done_) engine->on_event_done(on_done_);
    if (paused) engine->pause();  // handled right after the engine's start
    engine->start();
    std::unique_ptr<sync::SyncEngine> old;
    {
        std::lock_guard lock(mu_);
        old = std::move(engine_);
        engine_ = std::move(engine);
    }
    if (!old) return;
    old->stop();
    // What the replaced engine fell short of stays the print's (result.json).
    const sync::SyncStatus last = old->status();
    std::lock_guard lock(mu_);
    for (const sync::Shortfall& f : last.stats.shortfalls)
        if (earlier_shortfalls_.size() < sync::max_shortfalls) earlier_shortfalls_.push_back(f);
}

void PrintSession::pause() {
    std::lock_guard lock(mu_);
    if (status_.phase != PrintPhase::printing)
        throw PrintError("pause: the print is " + std::string(to_string(status_.phase)));
    engine_->pause();
    status_.phase = PrintPhase::paused;
}

void PrintSession::resume() {
    PrintPhase phase;
    {
        std::lock_guard lock(mu_);
        phase = status_.phase;
    }
    if (phase == PrintPhase::paused) {
        std::lock_guard lock(mu_);
        engine_->resume();
        status_.phase = PrintPhase::printing;
        return;
    }
    if (phase != PrintPhase::faulted)
        throw PrintError("resume: the print is " + std::string(to_string(phase)));
    if (!links_.robot_io.wait_until_up(options_.link_timeout))
        throw PrintError("resume: the robot I/O link is still down (" +
                         links_.robot_io.snapshot().fault_reason + ")");
    if (links_.board.state() != drivers::DeviceState::active)
        throw PrintError("resume: the extruder board is not connected");
    abb::FcStatus robot;
    try {
        robot = fc_.status();
    } catch (const std::exception& e) {
        throw PrintError(std::string("resume: cannot read the robot program: ") + e.what());
    }
    if (robot.state != abb::FcState::held && robot.state != abb::FcState::paused &&
        robot.state != abb::FcState::running)
        throw PrintError("resume: the robot program is " + std::string(abb::to_string(robot.state)) +
                         (robot.message.empty() ? "" : " (" + robot.message + ")") +
                         ": the run cannot be continued");
    const sync::SyncStatus s = settled_engine_status();
    if (s.faulted) {
        // A new engine after the last confirmed event, first metering the rest of a path the
        // fault interrupted; paused until the robot is re-armed, so the metering starts with it.
        std::optional<sync::ResumeFeed> feed;
        if (s.metering.sequence > 0 && s.metering.sequence <= s.last_confirmed)
            feed = sync::ResumeFeed{s.metering.sequence, s.metering.e_fed_mm};
        start_engine(s.last_confirmed + 1, feed, true);
        // The robot may stand at an event the faulted engine never finished (a barrier whose
        // release it waits for): no counter change will come for it, so the new engine takes the
        // counter as it reads now (a value it has confirmed already is a duplicate to it).
        const abb::RobotIoSnapshot io = links_.robot_io.snapshot();
        const auto now = abb::IoClock::now();
        std::lock_guard lock(mu_);
        engine_->robot_event({std::nullopt, io.event_counter, io.barrier, now, now});
    }
    if (robot.state == abb::FcState::held) rearm_after_hold();
    std::lock_guard lock(mu_);
    engine_->resume();
    status_.phase = PrintPhase::printing;
    status_.reason.clear();
}

// FcMain takes a resume after a heartbeat loss only from a pause request that rises while the
// heartbeat is back (FcOnPause arms it, FcOnResume takes it). The link may have written the pause
// before the heartbeat resumed, so make a fresh rising edge once the heartbeat has run a while.
// The engine's status once the board has answered every metering piece sent before a fault
// (the aborted ones answer at once; at most a second for the ones the firmware runs out).
sync::SyncStatus PrintSession::settled_engine_status() const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    for (;;) {
        sync::SyncStatus s;
        {
            std::lock_guard lock(mu_);
            s = engine_->status();
        }
        if (s.metering.pieces_unanswered == 0 || std::chrono::steady_clock::now() > deadline)
            return s;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
}

// FcMain toggles its heartbeat once its cycle is set up; a run request before that is dropped.
void PrintSession::wait_for_robot_heartbeat() {
    const auto deadline = Clock::now() + options_.run_request_timeout;
    while (!links_.robot_io.snapshot().robot_heartbeat_ok) {
        if (Clock::now() > deadline)
            throw PrintError("pre-flight: no heartbeat from the robot program within " +
                             std::to_string(options_.run_request_timeout.count()) +
                             " ms (is FcMain running?)");
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

// A run starts with the service's outputs at rest: FcMain refuses one while the previous run's
// last barrier release is still standing (docs/modbus-map.md).
void PrintSession::reset_service_outputs() {
    links_.robot_io.set_release(0);
    links_.robot_io.set_pause(false);
    links_.robot_io.set_abort(false);
    std::this_thread::sleep_for(3 * links_.robot_io.config().poll_period);  // written by then
}

// A run left over from before a service restart (FcMain holding the robot on the lost heartbeat,
// or still running) is aborted so that the new run can start; the robot stands meanwhile.
void PrintSession::end_previous_run() {
    const abb::FcStatus s = fc_.status();
    if (s.state != abb::FcState::running && s.state != abb::FcState::paused &&
        s.state != abb::FcState::held)
        return;
    links_.robot_io.set_abort(true);
    const auto deadline = Clock::now() + options_.run_request_timeout;
    abb::FcState now = s.state;
    while (Clock::now() < deadline) {
        now = fc_.status().state;
        if (now != abb::FcState::running && now != abb::FcState::paused && now != abb::FcState::held) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    links_.robot_io.set_abort(false);
    links_.robot_io.set_pause(false);
    if (now == abb::FcState::running || now == abb::FcState::paused || now == abb::FcState::held)
        throw PrintError("pre-flight: the robot program's previous run (" +
                         std::string(abb::to_string(s.state)) + ") did not end on the abort request");
}

void PrintSession::rearm_after_hold() {
    // The heartbeat must be back (FcMain arms the resume only then); each attempt is a fresh
    // rise and drop of the pause request, a few heartbeats apart, until FcMain leaves `held`.
    const auto hb = links_.robot_io.config().heartbeat_period;
    const auto deadline = Clock::now() + options_.run_request_timeout;
    while (!links_.robot_io.snapshot().robot_heartbeat_ok && Clock::now() < deadline)
        std::this_thread::sleep_for(hb);
    for (int attempt = 0; attempt < 5; ++attempt) {
        links_.robot_io.set_pause(false);
        std::this_thread::sleep_for(3 * hb);
        links_.robot_io.set_pause(true);
        std::this_thread::sleep_for(3 * hb);
        links_.robot_io.set_pause(false);
        const auto until = Clock::now() + 10 * hb;
        while (Clock::now() < until) {
            if (fc_.status().state != abb::FcState::held) return;
            std::this_thread::sleep_for(hb);
        }
    }
    throw PrintError("resume: the robot program stays held after the heartbeat came back");
}

void PrintSession::abort(std::chrono::milliseconds timeout) {
    std::unique_ptr<sync::SyncEngine> engine;
    {
        std::lock_guard lock(mu_);
        engine = std::move(engine_);
    }
    if (engine) {
        engine->pause();
        engine->stop();
    }
    links_.board.abort();
    links_.robot_io.set_abort(true);
    const auto deadline = Clock::now() + timeout;
    std::string why = "aborted by the operator";
    for (;;) {
        try {
            const auto s = fc_.status();
            if (s.state == abb::FcState::aborted || s.state == abb::FcState::idle ||
                s.state == abb::FcState::completed)
                break;
        } catch (const std::exception& e) {
            why += std::string(" (robot status unreadable: ") + e.what() + ")";
        }
        if (Clock::now() > deadline) {
            why += "; the robot program did not confirm the abort within " +
                   std::to_string(timeout.count()) + " ms";
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    links_.robot_io.set_abort(false);
    links_.robot_io.set_pause(false);
    std::lock_guard lock(mu_);
    status_.phase = PrintPhase::aborted;
    status_.reason = why;
}

void PrintSession::fault(const std::string& reason) {
    // Robot-side faults leave the engine running: pause it so that no feed goes on. Its own
    // faults have stopped it already.
    if (engine_ && !engine_->status().faulted) engine_->pause();
    status_.phase = PrintPhase::faulted;
    status_.reason = reason;
}

PrintStatus PrintSession::poll() {
    abb::FcStatus robot;
    std::string robot_error;
    bool rapid_stopped = false;
    std::string build_log;
    try {
        robot = fc_.status();
        rapid_stopped = links_.rws.execution_state().state == abb::rws::ExecutionState::stopped;
        // A chunk that does not build stops RAPID in WaitLoad; the build log says where.
        if (rapid_stopped)
            for (const auto& e : links_.rws.build_errors())
                build_log += (build_log.empty() ? "" : "; ") + abb::rws::format(e);
    } catch (const std::exception& e) {
        robot_error = e.what();
    }
    std::lock_guard lock(mu_);
    if (engine_) {
        status_.sync = engine_->status();
        auto& all = status_.sync.stats.shortfalls;
        all.insert(all.begin(), earlier_shortfalls_.begin(), earlier_shortfalls_.end());
        if (all.size() > sync::max_shortfalls) all.resize(sync::max_shortfalls);
    }
    if (robot_error.empty()) status_.robot = robot;
    if (status_.phase != PrintPhase::printing && status_.phase != PrintPhase::paused)
        return status_;
    if (status_.sync.faulted) {
        fault(status_.sync.fault_reason);
    } else if (!robot_error.empty()) {
        fault("robot controller unreachable: " + robot_error);
    } else if (rapid_stopped && robot.state != abb::FcState::completed) {
        fault("RAPID execution stopped on the controller" +
              (build_log.empty() ? std::string() : ": " + build_log));
    } else if (robot.state == abb::FcState::completed) {
        if (status_.sync.finished) status_.phase = PrintPhase::completed;
    } else if (robot.state == abb::FcState::held) {
        fault("robot held: " + robot.message);
    } else if (robot.state != abb::FcState::running && robot.state != abb::FcState::paused) {
        fault("the robot program stopped the run (" + std::string(abb::to_string(robot.state)) +
              (robot.message.empty() ? "" : ": " + robot.message) + ")");
    }
    return status_;
}

PrintPhase PrintSession::wait_until_done(std::chrono::milliseconds timeout,
                                         std::chrono::milliseconds period) {
    const auto deadline = Clock::now() + timeout;
    for (;;) {
        const PrintPhase p = poll().phase;
        if (finished(p) || Clock::now() > deadline) return p;
        std::this_thread::sleep_for(period);
    }
}

}  // namespace fibrecell::daemon::print
