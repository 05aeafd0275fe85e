// Sync engine latency at time scale 1 (docs/sync-engine.md): from the simulated robot changing
// its event counter (RobotIoServer::set_event_number) to the event's first board command written
// to the serial port (MarlinLink::on_bytes_written) and executed by the mock GT2560 (its log time
// mapped with wall_at), median and p99, over a program of many short events: head switches
// (barriers), cuts, path ends, retracts, layer ends. Each event waits until the previous one is
// done, so the board is idle when it comes, as between a robot's events. Also prints the engine's
// own measurement per kind. Release build; numbers are reported only (target p99 <= 5 ms).
#include "daemon/sync/sync_engine.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/sim/robot_io/robot_io_server.hpp"
#include "drivers/sim/mock_board/mock_gt2560.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <thread>
#include <vector>

using namespace fibrecell;
using namespace fibrecell::daemon::sync;
using drivers::abb::EventKind;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

namespace {

// Cycles of: head switch to CCF, cut, path end, head switch to PLA, retract, layer end.
drivers::abb::PrintProgram short_event_program(int cycles) {
    using drivers::abb::Nozzle;
    drivers::abb::PrintProgram p;
    const auto add = [&](EventKind kind, Nozzle nozzle, bool barrier) {
        drivers::abb::ProgramEvent e;
        e.sequence = static_cast<int>(p.events.size()) + 1;
        e.kind = kind;
        e.nozzle = nozzle;
        e.barrier = barrier;
        e.speed_mm_s = barrier ? 0 : 5;
        e.layer = static_cast<int>(p.events.size()) / 6;
        p.events.push_back(e);
    };
    for (int i = 0; i < cycles; ++i) {
        add(EventKind::head_switch, Nozzle::ccf, true);
        add(EventKind::cut, Nozzle::ccf, false);
        add(EventKind::path_end, Nozzle::ccf, false);
        add(EventKind::head_switch, Nozzle::pla, true);
        add(EventKind::extrude_off, Nozzle::pla, false);
        add(EventKind::layer_end, Nozzle::pla, false);
    }
    return p;
}

struct Summary {
    double median_ms = 0, p99_ms = 0, max_ms = 0;
};

Summary summarise(std::vector<double> ms) {
    if (ms.empty()) return {};
    std::sort(ms.begin(), ms.end());
    return {ms[ms.size() / 2], ms[ms.size() * 99 / 100], ms.back()};
}

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

template <class Pred>
bool wait_for(Pred pred, std::chrono::milliseconds timeout) {
    const auto end = Clock::now() + timeout;
    while (!pred()) {
        if (Clock::now() > end) return false;
        std::this_thread::sleep_for(50us);
    }
    return true;
}

}  // namespace

int main() {
    spdlog::set_level(spdlog::level::warn);
    std::string tmpl = (std::filesystem::temp_directory_path() / "sync-bench-XXXXXX").string();
    const std::filesystem::path dir = mkdtemp(tmpl.data());

    // The board, hotends quick to heat so that the preheat takes about a second.
    drivers::sim::MockGt2560Options mo;
    mo.bootloader_s = 0.01;
    mo.hotend_tau_s = 0.2;
    mo.residency_s = 0.1;
    mo.link_path = (dir / "ttyGT2560").string();
    drivers::sim::MockGt2560 mock(mo);
    drivers::marlin::MarlinLink board;
    drivers::marlin::MarlinLinkConfig lc;
    lc.serial.device = mock.port_path();
    board.configure(lc);
    board.activate();
    drivers::ExtruderConfig xc;
    xc.retract_mm = 0.05;    // short board moves: the bench measures the host path
    xc.cutter.hold_ms = 1;
    drivers::ExtruderController extruder(xc);
    board.submit(extruder.prepare({}, true)).get();

    drivers::sim::RobotIoServer server(drivers::abb::RobotIoMap{});
    drivers::abb::RobotIoConfig rc;
    rc.host = server.host();
    rc.port = server.port();
    rc.poll_period = 2ms;
    rc.stable_reads = 1;
    rc.stats_log_period = 0s;
    drivers::abb::RobotIoLink robot(rc);

    constexpr int cycles = 300;
    const auto program = short_event_program(cycles);
    SyncEngine engine(program, extruder, board, robot, {});
    robot.on_event([&](const auto& c) { engine.robot_event(c); });
    robot.on_state([&](const auto& c) { engine.robot_link_state(c); });
    board.on_temperature([&](const auto& r) { engine.board_temperature(r); });
    std::atomic<bool> armed{false};
    std::atomic<Clock::rep> first_write{0};
    board.on_bytes_written([&] {
        Clock::rep none = 0;
        if (armed) first_write.compare_exchange_strong(none, Clock::now().time_since_epoch().count());
    });
    robot.start();
    if (!robot.wait_until_up(5s)) {
        std::printf("robot I/O link not up: %s\n", robot.snapshot().last_error.c_str());
        return 1;
    }
    engine.start();
    wait_for([&] { return engine.status().pla_hotend_c && engine.status().ccf_hotend_c; }, 5s);

    std::mt19937 rng(42);
    std::uniform_int_distribution<int> phase_us(0, 4000);  // events at random phases of the poll
    std::vector<double> to_written, to_executed;
    int lost = 0;
    for (const auto& e : program.events) {
        std::this_thread::sleep_for(std::chrono::microseconds(phase_us(rng)));
        const bool has_commands = e.kind != EventKind::path_end && e.kind != EventKind::layer_end;
        const std::size_t log_before = mock.executed_count();
        first_write = 0;
        armed = has_commands;
        const auto n = static_cast<std::uint16_t>(e.sequence);
        const auto t0 = Clock::now();
        if (e.barrier) server.set_barrier_number(n);
        server.set_event_number(n);
        const bool done =
            wait_for([&] { return engine.status().last_confirmed >= e.sequence; }, 2s) &&
            (!e.barrier ||
             server.wait_for_commands([&](const auto& c) { return c.release == n; }, 2s));
        if (!done) {
            ++lost;
            continue;
        }
        armed = false;
        if (!has_commands) continue;
        if (first_write.load() != 0)
            to_written.push_back(ms_between(t0, Clock::time_point(Clock::duration(first_write.load()))));
        const auto log = mock.executed();
        if (log.size() > log_before) to_executed.push_back(ms_between(t0, mock.wall_at(log[log_before].t_s)));
    }
    const SyncStatus s = engine.status();
    engine.stop();
    robot.stop();
    board.on_temperature(nullptr);

    const Summary w = summarise(to_written), x = summarise(to_executed);
    std::printf("%d events (%zu with board commands), time scale 1, poll 2 ms, stable_reads 1; "
                "lost %d, faulted %s\n",
                static_cast<int>(program.events.size()), to_written.size(), lost,
                s.faulted ? s.fault_reason.c_str() : "no");
    std::printf("counter change -> first command written   median %6.2f ms  p99 %6.2f ms  max %6.2f ms\n",
                w.median_ms, w.p99_ms, w.max_ms);
    std::printf("counter change -> first command executed  median %6.2f ms  p99 %6.2f ms  max %6.2f ms\n",
                x.median_ms, x.p99_ms, x.max_ms);
    std::printf("engine's own measurement, from the poll that first read the change:\n");
    for (const KindTiming& k : s.stats.timing)
        std::printf("  %-12s n=%4zu  submit median %5.2f p99 %5.2f ms  ok median %5.2f p99 %5.2f ms  "
                    "position error p99 %.4f mm\n",
                    std::string(to_string(k.kind)).c_str(), k.submit_ms.count, k.submit_ms.median,
                    k.submit_ms.p99, k.ok_ms.median, k.ok_ms.p99, k.position_error_mm.p99);
    if (board.state() == drivers::DeviceState::active) board.deactivate();
    std::filesystem::remove_all(dir);
    return s.faulted || lost > 0 ? 1 : 0;
}
