#include "drivers/sim/mock_board/board_state.hpp"

#include "config/thread_priority.hpp"

#include <poll.h>
#include <unistd.h>

#include <thread>

namespace fibrecell::drivers::sim {

// ---- The firmware loop ----------------------------------------------------------------

void MockGt2560::Impl::run() {
    char buf[512];
    while (!stop.load()) {
        int fd;
        {
            std::lock_guard lock(mu);
            fd = unplugged ? -1 : pty.master();
        }
        if (fd < 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            continue;
        }
        pollfd p{fd, POLLIN, 0};
        ::poll(&p, 1, 1);
        if (tick(fd, p.revents, buf, sizeof buf))
            std::this_thread::sleep_for(std::chrono::milliseconds(1));  // POLLHUP stays up
    }
}

// One pass of the firmware loop; returns true while the port is closed (nobody reading).
bool MockGt2560::Impl::tick(int fd, short revents, char* buf, std::size_t size) {
    std::lock_guard lock(mu);
    if (unplugged || pty.master() != fd) return false;
    const double t = now();
    if (!connected && !(revents & POLLHUP)) {
        connected = true;  // the host opened the port: DTR pulses the reset line
        if (o.reset_on_open) reboot(false, t);
    }
    // Bytes the host wrote just before closing still arrive (its last M112, for one).
    if (revents & POLLIN) {
        const ssize_t n = ::read(fd, buf, size);
        for (ssize_t i = 0; i < n; ++i) on_byte(buf[i]);
    }
    if (connected) step(t);
    if (revents & POLLHUP) {
        connected = false;
        return true;
    }
    return false;
}

MockGt2560::MockGt2560(MockGt2560Options options)
    : impl_(std::make_unique<Impl>(std::move(options))) {
    impl_->keepalive_s = impl_->o.keepalive_s;
    for (auto& h : impl_->heaters) h.temp_c = impl_->o.ambient_c;
    impl_->open_pty();
    if (!impl_->o.reset_on_open) impl_->reboot(false, 0);
    impl_->thread = std::thread([this] {
        config::make_thread_time_critical("sim.board");
        impl_->run();
    });
}

MockGt2560::~MockGt2560() {
    impl_->stop = true;
    impl_->thread.join();
    impl_->close_pty();
}

std::string MockGt2560::port_path() const {
    std::lock_guard lock(impl_->mu);
    return impl_->pty.port_path();
}

double MockGt2560::sim_now_s() const {
    return impl_->now();
}

std::chrono::steady_clock::time_point MockGt2560::wall_at(double sim_s) const {
    return impl_->t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(sim_s / impl_->o.time_scale));
}

void MockGt2560::corrupt_line(std::int64_t k) { impl_->mark(impl_->corrupt, k); }
void MockGt2560::drop_line(std::int64_t k) { impl_->mark(impl_->drop, k); }
void MockGt2560::duplicate_line(std::int64_t k) { impl_->mark(impl_->duplicate, k); }
void MockGt2560::swallow_ok(std::int64_t k) { impl_->mark(impl_->swallow, k); }
void MockGt2560::delay_ok(std::int64_t k, double sim_s) {
    std::lock_guard lock(impl_->mu);
    impl_->delay[k] = sim_s;
}
void MockGt2560::garble_next_resend() {
    std::lock_guard lock(impl_->mu);
    impl_->garble_resend = true;
}
void MockGt2560::reset_at_line(std::int64_t k) {
    std::lock_guard lock(impl_->mu);
    impl_->reset_at = k;
}
void MockGt2560::reset_now() {
    std::lock_guard lock(impl_->mu);
    impl_->reboot(true, impl_->now());
}
void MockGt2560::go_silent(bool silent) {
    std::lock_guard lock(impl_->mu);
    impl_->silent = silent;
}
void MockGt2560::unplug() {
    std::lock_guard lock(impl_->mu);
    impl_->close_pty();
    impl_->unplugged = true;
    impl_->connected = false;
}
void MockGt2560::replug() {
    std::lock_guard lock(impl_->mu);
    if (!impl_->unplugged) return;
    impl_->open_pty();
    impl_->reboot(false, impl_->now());  // power comes back with the cable
}
void MockGt2560::thermal_runaway(int heater) {
    std::lock_guard lock(impl_->mu);
    impl_->runaway = heater;
}
void MockGt2560::send_action(const std::string& action) {
    std::lock_guard lock(impl_->mu);
    impl_->actions.push_back(action);
}

std::vector<ExecutedCommand> MockGt2560::executed() const {
    std::lock_guard lock(impl_->mu);
    return {impl_->executed.begin(), impl_->executed.end()};
}
std::vector<ExecutedCommand> MockGt2560::executed_since(std::size_t first) const {
    std::lock_guard lock(impl_->mu);
    const std::size_t skip = first > impl_->executed_dropped ? first - impl_->executed_dropped : 0;
    if (skip >= impl_->executed.size()) return {};
    return {impl_->executed.begin() + static_cast<std::ptrdiff_t>(skip), impl_->executed.end()};
}
std::size_t MockGt2560::executed_count() const {
    std::lock_guard lock(impl_->mu);
    return impl_->executed_dropped + impl_->executed.size();
}
std::vector<PinEvent> MockGt2560::pin_events() const {
    std::lock_guard lock(impl_->mu);
    return {impl_->pins.begin(), impl_->pins.end()};
}
double MockGt2560::temperature_c(int heater) const {
    std::lock_guard lock(impl_->mu);
    return impl_->heaters.at(static_cast<std::size_t>(heater)).temp_c;
}
double MockGt2560::target_c(int heater) const {
    std::lock_guard lock(impl_->mu);
    return impl_->heaters.at(static_cast<std::size_t>(heater)).target_c;
}
bool MockGt2560::killed() const {
    std::lock_guard lock(impl_->mu);
    return impl_->killed;
}
std::uint64_t MockGt2560::cold_extrusion_refusals() const {
    std::lock_guard lock(impl_->mu);
    return impl_->cold_refusals;
}

std::uint64_t MockGt2560::rx_bytes_dropped() const {
    std::lock_guard lock(impl_->mu);
    return impl_->dropped;
}
bool MockGt2560::wait_for_executed(std::size_t n, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(impl_->mu);
    return impl_->cv.wait_for(
        lock, timeout, [&] { return impl_->executed_dropped + impl_->executed.size() >= n; });
}

}  // namespace fibrecell::drivers::sim
