#include "drivers/abb/modbus/robot_io_link.hpp"

#include "config/thread_priority.hpp"
#include "drivers/abb/modbus/input_filters.hpp"
#include "drivers/abb/modbus/modbus_errors.hpp"
#include "drivers/abb/modbus/modbus_read_plan.hpp"

#include <modbus.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>

namespace fibrecell::drivers::abb {
namespace {

using std::chrono::duration_cast;
using std::chrono::milliseconds;

constexpr std::size_t event_queue_capacity = 4096;

// Output bits, in the order they are rewritten after a reconnect: pause first (docs/modbus-map.md,
// "Link loss"), the heartbeat last.
enum OutputBit : unsigned {
    out_pause = 1,
    out_abort = 2,
    out_release = 4,
    out_chunk_ready = 8,
    out_heartbeat = 16,
    out_all = 31,
};

double gap_ms(IoClock::time_point a, IoClock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

long long ms_between(IoClock::time_point a, IoClock::time_point b) {
    return duration_cast<milliseconds>(b - a).count();
}

}  // namespace

std::string_view to_string(RobotIoState s) {
    switch (s) {
        case RobotIoState::stopped:
            return "stopped";
        case RobotIoState::connecting:
            return "connecting";
        case RobotIoState::up:
            return "up";
        case RobotIoState::fault:
            return "fault";
    }
    return "?";
}

struct RobotIoLink::Impl {
    const RobotIoConfig cfg;
    const std::string endpoint;  // "modbus 127.0.0.1:1502"
    const ReadPlan plan;

    // Shared with other threads, guarded by mu.
    mutable std::mutex mu;
    std::condition_variable wake;             // the link thread: stop, outputs changed
    mutable std::condition_variable changed;  // wait_until_up()
    bool stop_requested = false;
    bool quiet_stop = false;  // the destructor: no callbacks on the way out
    RobotIoOutputs desired;
    unsigned dirty = 0;
    RobotIoSnapshot snap;
    std::deque<EventCounterChange> queue;
    std::atomic<IoClock::rep> alive_at{0};

    std::function<void(const EventCounterChange&)> event_cb;
    std::function<void(const RobotIoStateChange&)> state_cb;
    std::thread thread;

    // Link thread only.
    modbus_t* ctx = nullptr;
    RobotIoState state = RobotIoState::stopped;
    RobotIoStats stats;
    InputBuffers buffers;
    StableValue event;
    StableValue barrier;
    RobotHeartbeatWatch heartbeat;
    std::optional<IoClock::time_point> last_toggle;  // of heartbeat_out, this connection
    std::optional<IoClock::time_point> last_digest;  // the last successful read, this connection
    bool running = false;
    IoClock::time_point fault_since{};
    IoClock::time_point next_heartbeat{};
    IoClock::time_point next_stats{};
    bool stall_reported = false;

    explicit Impl(RobotIoConfig c)
        : cfg(std::move(c)),
          endpoint("modbus " + cfg.host + ":" + std::to_string(cfg.port)),
          plan(make_read_plan(cfg.map)),
          buffers(plan),
          heartbeat(cfg.robot_heartbeat_timeout) {}

    // --- helpers -------------------------------------------------------------------------------

    bool stopping() {
        std::lock_guard lock(mu);
        return stop_requested;
    }

    // Sleeps up to `d`; false when stop was requested.
    bool sleep_for(IoClock::duration d) {
        std::unique_lock lock(mu);
        return !wake.wait_for(lock, d, [&] { return stop_requested; });
    }

    std::string io_error_text(int err, const std::string& what) const {
        return modbus_error_text(err, endpoint, what, cfg.response_timeout);
    }

    void publish(const std::function<void(RobotIoSnapshot&)>& f) {
        {
            std::lock_guard lock(mu);
            f(snap);
            snap.state = state;
            snap.stats = stats;
            snap.outputs = desired;
        }
        changed.notify_all();
    }

    void set_state(RobotIoState to, const std::string& reason) {
        const RobotIoState from = state;
        if (from == to) return;
        state = to;
        const auto now = IoClock::now();
        // Callbacks first: once the snapshot shows a change, its callback has run.
        if (state_cb) state_cb({from, to, reason, now});
        publish(
            [&](RobotIoSnapshot& s) { s.fault_reason = to == RobotIoState::fault ? reason : ""; });
    }

    // --- connection ----------------------------------------------------------------------------

    void disconnect() {
        if (!ctx) return;
        modbus_close(ctx);
        modbus_free(ctx);
        ctx = nullptr;
        publish([](RobotIoSnapshot& s) { s.connected = false; });
    }

    // One connection attempt; "" on success, else the reason.
    std::string connect() {
        const std::string service = std::to_string(cfg.port);
        ctx = modbus_new_tcp_pi(cfg.host.c_str(), service.c_str());
        if (!ctx)
            return endpoint + ": cannot create a Modbus context (" + modbus_strerror(errno) + ")";
        const auto to_s = static_cast<std::uint32_t>(cfg.response_timeout.count() / 1000);
        const auto to_us = static_cast<std::uint32_t>((cfg.response_timeout.count() % 1000) * 1000);
        modbus_set_response_timeout(ctx, to_s, to_us);
        modbus_set_byte_timeout(ctx, to_s, to_us);
        modbus_set_error_recovery(ctx, MODBUS_ERROR_RECOVERY_NONE);
        if (modbus_set_slave(ctx, cfg.unit_id) == -1 || modbus_connect(ctx) == -1) {
            const int err = errno;
            modbus_free(ctx);
            ctx = nullptr;
            return endpoint + ": connect failed (" + modbus_strerror(err) + ")";
        }
        const auto now = IoClock::now();
        ++stats.connects;
        // Baselines restart with the connection; the accepted values and the watch stay armed.
        event.count = 0;
        barrier.count = 0;
        heartbeat.reconnected(now);
        next_heartbeat = now;
        last_toggle.reset();
        last_digest.reset();
        {
            std::lock_guard lock(mu);
            dirty = out_all;  // rewrite every output, pause first
        }
        publish([](RobotIoSnapshot& s) { s.connected = true; });
        return "";
    }

    // --- one cycle -----------------------------------------------------------------------------

    // Writes the outputs marked dirty; "" or the failure.
    std::string write_outputs() {
        RobotIoOutputs out;
        unsigned todo = 0;
        {
            std::lock_guard lock(mu);
            out = desired;
            todo = dirty;
            dirty = 0;
        }
        const RobotIoMap& m = cfg.map;
        // Each step: true when done (or nothing to do), false with errno set.
        auto coil = [&](unsigned bit, const ModbusAddress& a, bool v) {
            if (!(todo & bit)) return true;
            if (modbus_write_bit(ctx, a.address, v ? 1 : 0) == -1) return false;
            ++stats.requests;
            ++stats.writes;
            return true;
        };
        auto reg = [&](unsigned bit, const ModbusAddress& a, std::uint16_t v) {
            if (!(todo & bit)) return true;
            if (modbus_write_register(ctx, a.address, v) == -1) return false;
            ++stats.requests;
            ++stats.writes;
            return true;
        };
        unsigned failed = 0;
        const char* what = "";
        if (!coil(out_pause, m.pause_request, out.pause)) {
            failed = out_pause;
            what = "write pause_request";
        } else if (!coil(out_abort, m.abort_request, out.abort)) {
            failed = out_abort;
            what = "write abort_request";
        } else if (!reg(out_release, m.barrier_release, out.release)) {
            failed = out_release;
            what = "write barrier_release";
        } else if (m.chunk_ready && !reg(out_chunk_ready, *m.chunk_ready, out.chunk_ready)) {
            failed = out_chunk_ready;
            what = "write chunk_ready";
        } else if (!coil(out_heartbeat, m.heartbeat_out, out.heartbeat)) {
            failed = out_heartbeat;
            what = "write heartbeat_out";
        }
        if (failed) {
            const int err = errno;
            {
                std::lock_guard lock(mu);
                dirty |= todo & ~(failed - 1);  // this one and the ones not yet written
            }
            return io_error_text(err, what);
        }
        return "";
    }

    std::string read_inputs() {
        for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
            const ReadBlock& b = plan.blocks[i];
            int rc = -1;
            switch (b.table) {
                case ModbusTable::input_register:
                    rc =
                        modbus_read_input_registers(ctx, b.start, b.count, buffers.words[i].data());
                    break;
                case ModbusTable::holding_register:
                    rc = modbus_read_registers(ctx, b.start, b.count, buffers.words[i].data());
                    break;
                case ModbusTable::discrete_input:
                    rc = modbus_read_input_bits(ctx, b.start, b.count, buffers.bits[i].data());
                    break;
                case ModbusTable::coil:
                    rc = modbus_read_bits(ctx, b.start, b.count, buffers.bits[i].data());
                    break;
            }
            if (rc == -1) return io_error_text(errno, "read " + describe_block(b));
            ++stats.requests;
        }
        return "";
    }

    void toggle_heartbeat(IoClock::time_point now) {
        if (now < next_heartbeat) return;
        next_heartbeat += cfg.heartbeat_period;
        if (next_heartbeat < now) next_heartbeat = now + cfg.heartbeat_period;
        if (cfg.service_watchdog.count() > 0) {
            const auto alive = IoClock::time_point(IoClock::duration(alive_at.load()));
            if (now - alive > cfg.service_watchdog) {
                if (!stall_reported)
                    spdlog::error(
                        "robot_io.service_stalled no service_alive() for {} ms: "
                        "heartbeat_out stopped",
                        ms_between(alive, now));
                stall_reported = true;
                return;
            }
            stall_reported = false;
        }
        if (last_toggle)
            stats.heartbeat_gap_ms_max = std::max(stats.heartbeat_gap_ms_max, gap_ms(*last_toggle, now));
        last_toggle = now;
        {
            std::lock_guard lock(mu);
            desired.heartbeat = !desired.heartbeat;
            dirty |= out_heartbeat;
        }
    }

    // `log_event` names the log line: robot_io.link_lost or robot_io.robot_heartbeat_lost.
    void enter_fault(std::string_view log_event, const std::string& reason) {
        if (state != RobotIoState::up) return;  // already in fault, or never up: `connecting`
        ++stats.faults;
        fault_since = IoClock::now();
        spdlog::error("{} {}", log_event, reason);
        if (cfg.pause_on_fault) {
            std::lock_guard lock(mu);
            if (!desired.pause) dirty |= out_pause;
            desired.pause = true;
        }
        set_state(RobotIoState::fault, reason);
    }

    // After a successful read: filters, heartbeat watch, events, state.
    void digest(IoClock::time_point now) {
        // A read long after the one before: this process did not run (SIGSTOP, a frozen VM, a
        // machine too busy). The robot's heartbeat went unread, not missing; ours stopped, and
        // FcMain held the robot on it. Said as what it was, and the robot's watch starts over.
        if (last_digest && now - *last_digest > cfg.robot_heartbeat_timeout) {
            heartbeat.restart_age(now);
            enter_fault("robot_io.service_not_running",
                        "fibrecelld itself did not run for " +
                            std::to_string(ms_between(*last_digest, now)) +
                            " ms (stopped, e.g. SIGSTOP, or starved of CPU): its heartbeat to the "
                            "robot stopped, and FcMain held the robot");
        }
        last_digest = now;
        const RobotIoMap& m = cfg.map;
        const std::uint16_t ev = buffers.word(plan, m.event_number);
        const std::uint16_t br = buffers.word(plan, m.barrier_number);
        running = buffers.bit(plan, m.robot_running);

        const auto previous_event = event.accepted;
        const bool event_changed = event.update(ev, now, cfg.stable_reads, stats.torn_reads);
        barrier.update(br, now, cfg.stable_reads, stats.torn_reads);

        const RobotHeartbeatWatch::Reading hb =
            heartbeat.read(buffers.bit(plan, m.heartbeat_in), now);
        if (hb.gap_ms)
            stats.robot_heartbeat_gap_ms_max =
                std::max(stats.robot_heartbeat_gap_ms_max, *hb.gap_ms);

        std::optional<EventCounterChange> change;
        if (event_changed) {
            ++stats.event_changes;
            change =
                EventCounterChange{previous_event, *event.accepted, barrier.accepted.value_or(0),
                                   event.first_read, IoClock::now()};
            std::lock_guard lock(mu);
            if (queue.size() >= event_queue_capacity) {
                queue.pop_front();
                ++stats.events_dropped;
            }
            queue.push_back(*change);
        }
        if (change && event_cb) event_cb(*change);
        publish([&](RobotIoSnapshot& s) {
            s.event_counter = event.accepted.value_or(0);
            s.barrier = barrier.accepted.value_or(0);
            s.running = running;
            s.robot_heartbeat_ok = hb.ok;
            s.last_poll = now;
        });

        if (hb.lost_now) {
            const std::string reason =
                "robot heartbeat lost for " + std::to_string(hb.still_ms) + " ms";
            if (state == RobotIoState::up) {
                enter_fault("robot_io.robot_heartbeat_lost", reason);
            } else {
                spdlog::warn("robot_io.robot_heartbeat_lost {}", reason);
                if (state == RobotIoState::fault)
                    publish([&](RobotIoSnapshot& s) { s.last_error = reason; });
            }
        }
        const bool healthy = !heartbeat.armed() || hb.ok;
        if (healthy && state == RobotIoState::connecting) {
            spdlog::info("robot_io.link_up {} unit={} poll_period_us={}", endpoint, cfg.unit_id,
                         cfg.poll_period.count());
            set_state(RobotIoState::up, "connected");
        } else if (healthy && state == RobotIoState::fault) {
            const std::string reason =
                "recovered after " + std::to_string(ms_between(fault_since, now)) + " ms";
            spdlog::info("robot_io.link_restored {} {}", endpoint, reason);
            set_state(RobotIoState::up, reason);
        }
    }

    void log_stats(IoClock::time_point now) {
        if (cfg.stats_log_period.count() == 0 || now < next_stats) return;
        next_stats = now + cfg.stats_log_period;
        spdlog::info(
            "robot_io.stats state={} polls={} requests={} writes={} events={} torn={} faults={} "
            "connects={} poll_us_last={:.0f} poll_us_max={:.0f} heartbeat_gap_ms_max={:.0f} "
            "robot_heartbeat_gap_ms_max={:.0f}",
            to_string(state), stats.polls, stats.requests, stats.writes, stats.event_changes,
            stats.torn_reads, stats.faults, stats.connects, stats.poll_us_last, stats.poll_us_max,
            stats.heartbeat_gap_ms_max, stats.robot_heartbeat_gap_ms_max);
    }

    // --- the thread ----------------------------------------------------------------------------

    void on_io_failure(const std::string& reason) {
        disconnect();
        publish([&](RobotIoSnapshot& s) { s.last_error = reason; });
        if (state == RobotIoState::up) {
            enter_fault("robot_io.link_lost", reason);
        } else {
            spdlog::debug("robot_io.io_error {}", reason);
        }
    }

    void run() {
        auto backoff = cfg.reconnect_backoff_min;
        bool warned_connect = false;
        set_state(RobotIoState::connecting, "started");
        next_stats = IoClock::now() + cfg.stats_log_period;
        while (!stopping()) {
            if (!ctx) {
                const std::string err = connect();
                if (!err.empty()) {
                    ++stats.connect_failures;
                    publish([&](RobotIoSnapshot& s) { s.last_error = err; });
                    if (!warned_connect)
                        spdlog::warn("robot_io.connect_failed {}, retrying with back-off", err);
                    else
                        spdlog::debug("robot_io.connect_failed {} next_try_ms={}", err,
                                      backoff.count());
                    warned_connect = true;
                    if (!sleep_for(backoff)) break;
                    backoff = std::min(backoff * 2, cfg.reconnect_backoff_max);
                    continue;
                }
                warned_connect = false;
                spdlog::debug("robot_io.connected {}", endpoint);
            }
            auto next_poll = IoClock::now();
            std::string err;
            while (err.empty()) {
                // One poll cycle: outputs, inputs, digest.
                const auto t0 = IoClock::now();
                toggle_heartbeat(t0);
                err = write_outputs();
                if (!err.empty()) break;
                err = read_inputs();
                if (!err.empty()) break;
                const auto t1 = IoClock::now();
                ++stats.polls;
                stats.poll_us_last = std::chrono::duration<double, std::micro>(t1 - t0).count();
                stats.poll_us_max = std::max(stats.poll_us_max, stats.poll_us_last);
                digest(t1);
                if (state == RobotIoState::up) backoff = cfg.reconnect_backoff_min;
                log_stats(t1);
                // Wait for the next poll; write outputs at once when they change meanwhile.
                next_poll += cfg.poll_period;
                if (next_poll < IoClock::now()) next_poll = IoClock::now();
                for (;;) {
                    std::unique_lock lock(mu);
                    wake.wait_until(lock, next_poll, [&] { return stop_requested || dirty != 0; });
                    if (stop_requested) break;
                    if (dirty == 0) break;  // time to poll
                    lock.unlock();
                    err = write_outputs();
                    if (!err.empty()) break;
                }
                if (stopping()) break;
            }
            if (stopping()) break;
            on_io_failure(err);
            if (!sleep_for(backoff)) break;
            backoff = std::min(backoff * 2, cfg.reconnect_backoff_max);
        }
        disconnect();
        bool quiet = false;
        {
            std::lock_guard lock(mu);
            quiet = quiet_stop;
        }
        if (quiet) state_cb = nullptr;
        set_state(RobotIoState::stopped, "stopped");
    }
};

RobotIoLink::RobotIoLink(RobotIoConfig config) {
    validate(config);
    impl_ = std::make_unique<Impl>(std::move(config));
    impl_->alive_at = IoClock::now().time_since_epoch().count();
}

RobotIoLink::~RobotIoLink() {
    {
        std::lock_guard lock(impl_->mu);
        impl_->quiet_stop = true;
    }
    stop();
}

void RobotIoLink::on_event(std::function<void(const EventCounterChange&)> f) {
    if (impl_->thread.joinable()) throw RobotIoError("robot_io: set on_event() before start()");
    impl_->event_cb = std::move(f);
}

void RobotIoLink::on_state(std::function<void(const RobotIoStateChange&)> f) {
    if (impl_->thread.joinable()) throw RobotIoError("robot_io: set on_state() before start()");
    impl_->state_cb = std::move(f);
}

void RobotIoLink::start() {
    Impl& m = *impl_;
    if (m.thread.joinable()) return;
    {
        std::lock_guard lock(m.mu);
        m.stop_requested = false;
    }
    m.thread = std::thread([&m] {
        config::make_thread_time_critical("robot_io.poll");
        m.run();
    });
}

void RobotIoLink::stop() {
    Impl& m = *impl_;
    if (!m.thread.joinable()) return;
    {
        std::lock_guard lock(m.mu);
        m.stop_requested = true;
    }
    m.wake.notify_all();
    m.thread.join();
    spdlog::info("robot_io.stopped {}", m.endpoint);
}

bool RobotIoLink::wait_until_up(std::chrono::milliseconds timeout) const {
    std::unique_lock lock(impl_->mu);
    return impl_->changed.wait_for(lock, timeout,
                                   [&] { return impl_->snap.state == RobotIoState::up; });
}

RobotIoSnapshot RobotIoLink::snapshot() const {
    std::lock_guard lock(impl_->mu);
    RobotIoSnapshot s = impl_->snap;
    s.outputs = impl_->desired;
    return s;
}

RobotIoState RobotIoLink::state() const {
    std::lock_guard lock(impl_->mu);
    return impl_->snap.state;
}

std::vector<EventCounterChange> RobotIoLink::take_events() {
    std::lock_guard lock(impl_->mu);
    std::vector<EventCounterChange> out(impl_->queue.begin(), impl_->queue.end());
    impl_->queue.clear();
    return out;
}

namespace {
template <class T>
void set_output(std::mutex& mu, std::condition_variable& wake, RobotIoOutputs& desired,
                unsigned& dirty, T RobotIoOutputs::*field, T value, unsigned bit) {
    {
        std::lock_guard lock(mu);
        if (desired.*field == value) return;
        desired.*field = value;
        dirty |= bit;
    }
    wake.notify_all();
}
}  // namespace

void RobotIoLink::set_release(std::uint16_t barrier) {
    set_output(impl_->mu, impl_->wake, impl_->desired, impl_->dirty, &RobotIoOutputs::release,
               barrier, out_release);
}
void RobotIoLink::set_pause(bool on) {
    set_output(impl_->mu, impl_->wake, impl_->desired, impl_->dirty, &RobotIoOutputs::pause, on,
               out_pause);
}
void RobotIoLink::set_abort(bool on) {
    set_output(impl_->mu, impl_->wake, impl_->desired, impl_->dirty, &RobotIoOutputs::abort, on,
               out_abort);
}
void RobotIoLink::set_chunk_ready(std::uint16_t n) {
    if (!impl_->cfg.map.chunk_ready)
        throw RobotIoError(
            "robot_io: set_chunk_ready(): robot_io.map.chunk_ready is not configured");
    set_output(impl_->mu, impl_->wake, impl_->desired, impl_->dirty, &RobotIoOutputs::chunk_ready,
               n, out_chunk_ready);
}

void RobotIoLink::service_alive() {
    impl_->alive_at = IoClock::now().time_since_epoch().count();
}

const RobotIoConfig& RobotIoLink::config() const {
    return impl_->cfg;
}

}  // namespace fibrecell::drivers::abb
