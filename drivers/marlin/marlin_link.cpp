#include "drivers/marlin/marlin_link.hpp"

#include "config/thread_priority.hpp"
#include "drivers/marlin/serial_port.hpp"

#include <spdlog/spdlog.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>

#include <deque>
#include <thread>

namespace fibrecell::drivers::marlin {
namespace asio = boost::asio;

namespace {
constexpr auto tick_period = std::chrono::milliseconds(5);
}

struct MarlinLink::Impl {
    asio::io_context io;
    asio::executor_work_guard<asio::io_context::executor_type> guard = asio::make_work_guard(io);
    SerialPort port{io};
    asio::steady_timer ticker{io};
    std::thread thread;

    MarlinLinkConfig config;
    std::unique_ptr<MarlinProtocol> proto;
    std::array<char, 1024> rx_buf{};
    std::string rx_line;
    std::deque<std::string> tx_queue;
    bool writing = false;
    bool close_when_drained = false;

    struct Request {
        std::int64_t last_line;
        std::promise<CommandOutcome> done;
    };
    std::deque<Request> requests;
    // Lines that move or select an extruder, until their ok charges them to the ledger.
    std::deque<std::pair<std::int64_t, std::string>> feed_lines;
    bool cold_extrusion_refused = false;  // said before the ok of the line it refused

    mutable std::mutex mu;  // guards what other threads read
    std::map<std::string, bool> caps;
    ProtocolStats stats;
    LinkFailure failure = LinkFailure::none;
    std::string failure_detail;
    std::optional<Clock::time_point> failure_time;
    bool seen_start = false;
    FeedLedger ledger;
    std::function<void()> fault_to_state;

    std::function<void(const TemperatureReport&)> temperature_cb;
    std::function<void(const Reply&)> reply_cb;
    std::function<void()> written_cb;

    Impl() {
        thread = std::thread([this] {
            config::make_thread_time_critical("marlin.io");
            io.run();
        });
    }
    ~Impl() {
        asio::post(io, [this] { shut_port(); });
        guard.reset();
        thread.join();
    }

    // Runs `f` on the I/O thread and waits for it.
    template <class F>
    auto on_io(F f) -> decltype(f()) {
        std::packaged_task<decltype(f())()> task(std::move(f));
        auto fut = task.get_future();
        asio::post(io, [&task] { task(); });
        return fut.get();
    }

    void open() {
        port.open(config.serial);
        rx_line.clear();
        tx_queue.clear();
        writing = false;
        close_when_drained = false;
        {
            std::lock_guard lock(mu);
            caps.clear();
            failure = LinkFailure::none;
            failure_detail.clear();
            failure_time.reset();
            seen_start = false;
            ledger.firmware_started();  // opening the port resets the board
        }
        feed_lines.clear();
        cold_extrusion_refused = false;
        MarlinProtocol::Hooks hooks;
        hooks.write = [this](std::string_view bytes) { write(std::string(bytes)); };
        hooks.acked = [this](std::int64_t line) {
            if (!feed_lines.empty() && feed_lines.front().first <= line) {
                std::lock_guard lock(mu);
                while (!feed_lines.empty() && feed_lines.front().first <= line) {
                    const auto& [number, command] = feed_lines.front();
                    ledger.taken(command, !(cold_extrusion_refused && number == line));
                    feed_lines.pop_front();
                }
            }
            cold_extrusion_refused = false;
            while (!requests.empty() && requests.front().last_line <= line) {
                requests.front().done.set_value({});
                requests.pop_front();
            }
        };
        hooks.failed = [this](LinkFailure f, const std::string& detail) { on_failure(f, detail); };
        hooks.observed = [this](const Reply& r) { observe(r); };
        proto = std::make_unique<MarlinProtocol>(config.protocol, std::move(hooks));
        read_more();
        tick();
    }

    void shut_port() {
        ticker.cancel();
        port.close();
    }

    void observe(const Reply& r) {
        switch (r.kind) {
            case ReplyKind::start: {
                std::lock_guard lock(mu);
                seen_start = true;
                break;
            }
            case ReplyKind::capability: {
                std::lock_guard lock(mu);
                caps[r.capability] = r.capability_on;
                break;
            }
            case ReplyKind::error: spdlog::warn("extruder.firmware_error {}", r.text); break;
            case ReplyKind::line_error: spdlog::debug("extruder.line_error {}", r.text); break;
            case ReplyKind::action: spdlog::info("extruder.host_action {}", r.capability); break;
            case ReplyKind::echo:
                if (r.text.find("Unknown command") != std::string::npos)
                    spdlog::warn("extruder.unknown_command {}", r.text);
                if (r.text.find("cold extrusion prevented") != std::string::npos) {
                    spdlog::warn("extruder.cold_extrusion_prevented {}", r.text);
                    cold_extrusion_refused = true;
                }
                break;
            default: break;
        }
        if (r.temperatures && temperature_cb) temperature_cb(*r.temperatures);
        if (reply_cb) reply_cb(r);
    }

    void on_failure(LinkFailure f, const std::string& detail) {
        spdlog::error("extruder.link_fault reason={} {}", to_string(f), detail);
        {
            std::lock_guard lock(mu);
            failure = f;
            failure_detail = detail;
            failure_time = Clock::now();
            stats = proto->stats();
        }
        feed_lines.clear();  // never acknowledged: not charged
        if (fault_to_state) fault_to_state();  // before the requests learn of it
        fail_requests(f, detail);
        // Let queued bytes (the M112 itself) reach the wire before the port closes.
        if (writing) {
            close_when_drained = true;
        } else {
            shut_port();
        }
    }

    void fail_requests(LinkFailure f, const std::string& detail) {
        for (auto& r : requests) r.done.set_value({f, detail});
        requests.clear();
    }

    void read_more() {
        port.stream().async_read_some(
            asio::buffer(rx_buf), [this](const boost::system::error_code& ec, std::size_t n) {
                if (ec == asio::error::operation_aborted || !proto) return;
                if (ec || n == 0) {
                    proto->on_link_lost("serial read failed: " +
                                        (ec ? ec.message() : std::string("end of file")));
                    return;
                }
                const auto now = Clock::now();
                for (std::size_t i = 0; i < n && !proto->failed(); ++i) {
                    const char c = rx_buf[i];
                    if (c == '\n' || c == '\r') {
                        if (!rx_line.empty()) proto->on_line(rx_line, now);
                        rx_line.clear();
                    } else if (rx_line.size() < 4096) {
                        rx_line.push_back(c);
                    }
                }
                if (!proto->failed()) read_more();
            });
    }

    void write(std::string bytes) {
        tx_queue.push_back(std::move(bytes));
        if (!writing) write_next();
    }

    void write_next() {
        if (tx_queue.empty() || !port.is_open()) {
            writing = false;
            if (close_when_drained) shut_port();
            return;
        }
        writing = true;
        asio::async_write(port.stream(), asio::buffer(tx_queue.front()),
                          [this](const boost::system::error_code& ec, std::size_t) {
                              if (ec == asio::error::operation_aborted) return;
                              if (ec) {
                                  writing = false;
                                  if (proto) proto->on_link_lost("serial write failed: " + ec.message());
                                  return;
                              }
                              tx_queue.pop_front();
                              if (written_cb) written_cb();
                              write_next();
                          });
    }

    void tick() {
        ticker.expires_after(tick_period);
        ticker.async_wait([this](const boost::system::error_code& ec) {
            if (ec || !proto) return;
            proto->on_tick(Clock::now());
            {
                std::lock_guard lock(mu);
                stats = proto->stats();
            }
            if (!proto->failed()) tick();
        });
    }

    std::future<CommandOutcome> queue_lines(std::vector<std::string> lines, bool session_start) {
        return on_io([this, lines = std::move(lines), session_start] {
            std::promise<CommandOutcome> p;
            auto fut = p.get_future();
            if (!proto || proto->failed() || !port.is_open()) {
                p.set_value({proto ? proto->failure() : LinkFailure::link_lost,
                             "the link is not open"});
                return fut;
            }
            const auto now = Clock::now();
            std::int64_t last = -1;
            if (session_start) {
                proto->begin_session(0, now);
                last = 0;
            }
            for (const auto& l : lines) {
                last = proto->enqueue(l, now);
                std::string command = strip_comment(l);
                if (FeedLedger::counts(command)) feed_lines.emplace_back(last, std::move(command));
            }
            if (proto->failed()) {
                p.set_value({proto->failure(), failure_detail});
                return fut;
            }
            requests.push_back({last, std::move(p)});
            return fut;
        });
    }
};

MarlinLink::MarlinLink() : impl_(std::make_unique<Impl>()) {
    // Only a running link faults into `error`; a failing activation stays `inactive` and throws.
    impl_->fault_to_state = [this] {
        if (state_.load() == DeviceState::active) state_ = DeviceState::error;
    };
}

MarlinLink::~MarlinLink() = default;

void MarlinLink::transition(DeviceEvent e) {
    const auto next = next_state(state_.load(), e);
    if (!next)
        throw LinkError("extruder link: '" + std::string(to_string(e)) + "' is not allowed in state '" +
                        std::string(to_string(state_.load())) + "'");
    state_ = *next;
}

void MarlinLink::configure(MarlinLinkConfig config) {
    if (!next_state(state_.load(), DeviceEvent::configure)) transition(DeviceEvent::configure);
    impl_->on_io([&] { impl_->config = std::move(config); });
    transition(DeviceEvent::configure);
}

void MarlinLink::activate() {
    if (!next_state(state_.load(), DeviceEvent::activate)) transition(DeviceEvent::activate);
    Impl& m = *impl_;
    const MarlinLinkConfig cfg = m.on_io([&] { return m.config; });
    m.on_io([&] { m.open(); });
    auto give_up = [&](const std::string& why) {
        m.on_io([&] {
            m.fail_requests(LinkFailure::aborted, why);
            m.proto.reset();
            m.shut_port();
        });
        throw LinkError("extruder link " + cfg.serial.device + ": " + why);
    };
    // Opening an Arduino port resets the board: wait for its banner, or go on if none comes
    // (HUPCL was cleared before the last close and the board kept running).
    const auto boot_deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(cfg.boot_timeout);
    while (Clock::now() < boot_deadline) {
        {
            std::lock_guard lock(m.mu);
            if (m.seen_start) break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    const auto step = [&](std::future<CommandOutcome> f, const char* what) {
        if (f.wait_for(cfg.handshake_timeout) != std::future_status::ready)
            give_up(std::string(what) + " was not acknowledged");
        const CommandOutcome o = f.get();
        if (!o.ok()) give_up(std::string(what) + " failed: " + std::string(to_string(o.failure)) + " " + o.detail);
    };
    step(m.queue_lines({}, true), "line-number reset N0 M110 N0");
    step(m.queue_lines({"M115"}, false), "M115 capability query");
    const auto caps = capabilities();
    const auto autoreport = caps.find("AUTOREPORT_TEMP");
    if (cfg.autoreport_interval_s > 0 && autoreport != caps.end() && autoreport->second)
        step(m.queue_lines({"M155 S" + std::to_string(cfg.autoreport_interval_s)}, false),
             "M155 temperature auto-report");
    if (!emergency_parser())
        spdlog::warn("extruder.no_emergency_parser device={}: the firmware reports no "
                     "EMERGENCY_PARSER; an abort cannot break its heat-up and M112 is obeyed only "
                     "after a blocking command ends (build Marlin with EMERGENCY_PARSER)",
                     cfg.serial.device);
    transition(DeviceEvent::activate);
    spdlog::info("extruder.link_up device={} baud={}", cfg.serial.device, cfg.serial.baud_rate);
}

void MarlinLink::deactivate() {
    transition(DeviceEvent::deactivate);
    impl_->on_io([&] {
        impl_->fail_requests(LinkFailure::aborted, "the link was deactivated");
        impl_->proto.reset();
        impl_->shut_port();
    });
}

void MarlinLink::clear() {
    transition(DeviceEvent::clear);
    impl_->on_io([&] {
        impl_->proto.reset();
        impl_->shut_port();
    });
}

std::future<CommandOutcome> MarlinLink::submit(const std::vector<std::string>& gcode) {
    std::vector<std::string> lines;
    lines.reserve(gcode.size());
    for (std::size_t i = 0; i < gcode.size(); ++i) {
        std::string cmd = strip_comment(gcode[i]);
        if (cmd.empty()) continue;
        try {
            frame_line(99'999'999, cmd);  // the longest line number we will plausibly reach
        } catch (const LineError& e) {
            throw LineError("G-code line " + std::to_string(i + 1) + ": " + e.what());
        }
        if (is_emergency(cmd))
            throw LineError("G-code line " + std::to_string(i + 1) + ": '" + cmd +
                            "' is an emergency command: use abort(), quick_stop() or "
                            "emergency_stop()");
        lines.push_back(std::move(cmd));
    }
    if (state_.load() != DeviceState::active) {
        std::promise<CommandOutcome> p;
        p.set_value({LinkFailure::link_lost, "the extruder link is " +
                                                 std::string(to_string(state_.load())) +
                                                 ", not active"});
        return p.get_future();
    }
    return impl_->queue_lines(std::move(lines), false);
}

void MarlinLink::abort() {
    impl_->on_io([this] {
        Impl& m = *impl_;
        if (!m.proto || m.proto->failed()) return;
        m.proto->discard_unsent();
        const std::int64_t next = m.proto->next_line();
        // Never sent, never fed; and their numbers go to the next lines, whose oks must not
        // charge them.
        while (!m.feed_lines.empty() && m.feed_lines.back().first >= next) m.feed_lines.pop_back();
        // Requests that still had unsent lines are over; older ones complete with their oks.
        for (auto it = m.requests.begin(); it != m.requests.end();) {
            if (it->last_line >= next) {
                it->done.set_value({LinkFailure::aborted, "aborted by the host"});
                it = m.requests.erase(it);
            } else {
                ++it;
            }
        }
        m.proto->send_emergency("M108");
    });
}

void MarlinLink::quick_stop() {
    impl_->on_io([this] {
        if (impl_->proto && !impl_->proto->failed()) impl_->proto->send_emergency("M410");
    });
}

void MarlinLink::emergency_stop() {
    impl_->on_io([this] {
        if (impl_->proto && !impl_->proto->failed()) {
            impl_->proto->send_emergency("M112");  // raw, unnumbered, ahead of the queue
        }
    });
}

std::map<std::string, bool> MarlinLink::capabilities() const {
    std::lock_guard lock(impl_->mu);
    return impl_->caps;
}
bool MarlinLink::emergency_parser() const {
    std::lock_guard lock(impl_->mu);
    const auto it = impl_->caps.find("EMERGENCY_PARSER");
    return it != impl_->caps.end() && it->second;
}
FeedTotals MarlinLink::fed() const {
    std::lock_guard lock(impl_->mu);
    return impl_->ledger.totals();
}
ProtocolStats MarlinLink::stats() const {
    std::lock_guard lock(impl_->mu);
    return impl_->stats;
}
LinkFailure MarlinLink::fault() const {
    std::lock_guard lock(impl_->mu);
    return impl_->failure;
}
std::string MarlinLink::fault_detail() const {
    std::lock_guard lock(impl_->mu);
    return impl_->failure_detail;
}
std::optional<Clock::time_point> MarlinLink::fault_time() const {
    std::lock_guard lock(impl_->mu);
    return impl_->failure_time;
}

void MarlinLink::on_temperature(std::function<void(const TemperatureReport&)> f) {
    impl_->on_io([&] { impl_->temperature_cb = std::move(f); });
}
void MarlinLink::on_reply(std::function<void(const Reply&)> f) {
    impl_->on_io([&] { impl_->reply_cb = std::move(f); });
}
void MarlinLink::on_bytes_written(std::function<void()> f) {
    impl_->on_io([&] { impl_->written_cb = std::move(f); });
}

}  // namespace fibrecell::drivers::marlin
