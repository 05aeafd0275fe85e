// Cut position error at CCF speed, end to end (issue 6): the simulated IRC5 executing FcMain and
// the chunks, the mock GT2560 on a pseudo-terminal, and the service's real links and sync engine
// printing straight 50 mm fibre lines at 5 mm/s. For every cut: where the robot's TCP was (its
// recorded trajectory) when the board switched the cutter on, against the cut point, as path
// length; for every fibre path, the robot arriving at its start (where its fibre_start event
// fires) -> the board starting the thread feed. Also the engine's event -> first board command
// latency per kind. The simulated robot runs `time_scale` times faster than real time, and so
// does the robot's travel during the service's latency: the error at time scale s is about s
// times the real cell's, so run at 1 for the cell's figure (slow) and higher for a quick look.
//
// With --avr BUILD_DIR the board is gt2560-avr running the test firmware instead of the mock:
// real time (time scale 1), the cutter's D11 rising edge from its edge log, its clock mapped to
// the host's by status round trips during the print.
//
//   build/release/bench/print_bench [time_scale=2] [fibre_lines=12] [--avr BUILD_DIR]
#include "daemon/print/print_session.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"
#include "drivers/sim/cell/sim_cell.hpp"
#include "drivers/sim/mock_board/mock_gt2560.hpp"
#include "drivers/sim/motion/trajectory_analysis.hpp"
#include "gt2560_avr_process.hpp"
#include "tests/support/project_paths.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

using namespace fibrecell;
using namespace std::chrono_literals;
namespace abb = drivers::abb;

namespace {

abb::PrintProgram fibre_line_program(int lines) {
    std::vector<abb::RobotLayer> layers;
    const int per_layer = 6;
    for (int l = 0; l * per_layer < lines; ++l) {
        abb::RobotLayer ccf{.index = l, .z = 0.85 + 0.05 * l, .nozzle = abb::Nozzle::ccf};
        for (int k = 0; k < per_layer && l * per_layer + k < lines; ++k) {
            abb::RobotPath fibre{false, {}};
            for (int i = 0; i <= 5; ++i) fibre.points.emplace_back(110 + 10.0 * i, 130 + 8.0 * k);
            ccf.paths.push_back(fibre);
        }
        layers.push_back(ccf);
    }
    return abb::build_print_program(layers, abb::RobotCellConfig{},
                                    {.pla_speed_mm_s = 12, .ccf_speed_mm_s = 5, .cutter_distance_mm = 42});
}

double nearest_rank(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
    return v[std::min(v.size() - 1, k == 0 ? 0 : k - 1)];
}

using SteadyTime = std::chrono::steady_clock::time_point;

// When the board's pins did what the cut and the feed ask for, on the host's clock.
struct PinTimes {
    std::vector<SteadyTime> cutter_on;   // the cutter closing
    std::vector<SteadyTime> feed_start;  // a fibre feed move starting (E1 steps / a G1 E move)
};

// From gt2560-avr's edge log: D11 rising edges and E1 steps after a pause of over 50 ms (a new
// move), each simulated time mapped with the clock map taken nearest to it.
PinTimes avr_pin_times(bench::Gt2560AvrProcess& board, SteadyTime t_ref,
                       const std::vector<std::pair<double, double>>& maps /* (simulated s, offset s) */) {
    PinTimes out;
    if (maps.empty()) return out;
    const auto host = [&](double sim_s) {
        const auto nearest = std::min_element(maps.begin(), maps.end(), [&](const auto& a, const auto& b) {
            return std::abs(a.first - sim_s) < std::abs(b.first - sim_s);
        });
        return t_ref + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(sim_s + nearest->second));
    };
    board.status();
    double last_step = -1;
    for (const auto& e : board.new_edges()) {
        if (e.pin == "d11" && e.level == 1) out.cutter_on.push_back(host(e.t_s));
        if (e.pin != "e1_step" || e.level != 1) continue;
        if (last_step < 0 || e.t_s - last_step > 0.05) out.feed_start.push_back(host(e.t_s));
        last_step = e.t_s;
    }
    return out;
}

// From the mock's logs: its M42 S255 pin events and the start of each E move on tool 1.
PinTimes mock_pin_times(const drivers::sim::MockGt2560& mock) {
    PinTimes out;
    for (const auto& p : mock.pin_events())
        if (p.command.find("S255") != std::string::npos) out.cutter_on.push_back(mock.wall_at(p.t_s));
    bool ccf = false;
    for (const auto& c : mock.executed()) {
        if (c.text == "T0" || c.text == "T1") ccf = c.text == "T1";
        if (ccf && c.text.rfind("G1 E", 0) == 0 && c.move_start_s)
            out.feed_start.push_back(mock.wall_at(*c.move_start_s));
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    std::optional<std::string> avr_build;
    if (const auto at = std::find(args.begin(), args.end(), "--avr"); at != args.end()) {
        if (at + 1 == args.end()) {
            std::fprintf(stderr, "print_bench: --avr needs the build folder\n");
            return 2;
        }
        avr_build = *(at + 1);
        args.erase(at, at + 2);
    }
    const double scale = avr_build ? 1.0 : args.size() > 0 ? std::atof(args[0].c_str()) : 2.0;
    const int lines = args.size() > 1 ? std::atoi(args[1].c_str()) : 12;
    spdlog::set_level(spdlog::level::warn);
    const auto dir = std::filesystem::temp_directory_path() / "fibrecell-print-bench";
    std::filesystem::create_directories(dir);

    drivers::sim::SimCellOptions co;
    co.time_scale = scale;
    co.main_module = fibrecell::test::source_path("drivers/abb/rapid/FcMain.mod");
    drivers::sim::SimCell cell(co);
    drivers::sim::MockGt2560Options mo;
    mo.time_scale = scale;
    mo.bootloader_s = 0.2;
    mo.hotend_tau_s = 0.5;
    mo.residency_s = 0.2;
    mo.link_path = (dir / "ttyGT2560").string();
    drivers::sim::MockGt2560 mock(mo);
    std::optional<bench::Gt2560AvrProcess> avr;
    if (avr_build) {
        avr.emplace(*avr_build, dir);
        if (avr->port().empty()) {
            std::fprintf(stderr, "print_bench: gt2560-avr is not built in %s or did not start\n",
                         avr_build->c_str());
            return 1;
        }
    }

    std::mutex mu;
    daemon::print::PrintSession* session = nullptr;
    drivers::marlin::MarlinLink board;
    drivers::marlin::MarlinLinkConfig lc;
    lc.serial.device = avr ? avr->port() : mock.port_path();
    board.configure(lc);
    board.on_temperature([&](const auto& r) {
        std::lock_guard lock(mu);
        if (session) session->board_temperature(r);
    });
    board.activate();
    drivers::ExtruderController extruder{drivers::ExtruderConfig{}};
    abb::rws::RwsClient rws({.port = cell.rws_port()});
    abb::RobotIoConfig rc;
    rc.port = cell.modbus_port();
    rc.stable_reads = 1;
    abb::RobotIoLink robot(rc);
    robot.on_event([&](const auto& c) {
        std::lock_guard lock(mu);
        if (session) session->robot_event(c);
    });
    robot.on_state([&](const auto& c) {
        std::lock_guard lock(mu);
        if (session) session->robot_link_state(c);
    });
    robot.start();
    if (!robot.wait_until_up(5s)) {
        std::fprintf(stderr, "print_bench: robot I/O not up\n");
        return 1;
    }

    const abb::PrintProgram program = fibre_line_program(lines);
    std::vector<abb::ChunkFile> chunks;
    for (const auto& m : abb::write_rapid_chunks(program, abb::RobotCellConfig{}).modules)
        chunks.push_back({m.file_name, m.text});
    daemon::print::PrintOptions po;
    po.heartbeat_timeout_s = 1.0;  // real s: the simulated controller scales it
    po.sync.time_scale = scale;
    auto s = std::make_unique<daemon::print::PrintSession>(
        program, chunks, daemon::print::PrintLinks{rws, robot, board, extruder}, po);
    {
        std::lock_guard lock(mu);
        session = s.get();
    }
    std::printf("print_bench: %d fibre lines of 50 mm at 5 mm/s, time scale %.1f, %zu events, board %s\n",
                lines, scale, program.events.size(), avr ? "gt2560-avr (test firmware)" : "mock-gt2560");
    const auto t0 = std::chrono::steady_clock::now();
    s->start();
    // gt2560-avr's clock against the host's, every half second of the print.
    std::vector<std::pair<double, double>> maps;
    double worst_half_rtt_ms = 0;
    daemon::print::PrintPhase phase = s->poll().phase;
    for (;;) {
        phase = s->wait_until_done(avr ? 500ms : std::chrono::hours(2), 50ms);
        if (phase == daemon::print::PrintPhase::completed || phase == daemon::print::PrintPhase::faulted ||
            !avr)
            break;
        const auto m = avr->map_clock(t0);
        const double host_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        maps.emplace_back(host_s - m.offset_s, m.offset_s);
        worst_half_rtt_ms = std::max(worst_half_rtt_ms, m.half_rtt_ms);
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (phase != daemon::print::PrintPhase::completed) {
        std::fprintf(stderr, "print_bench: the print ended %s: %s\n",
                     std::string(daemon::print::to_string(phase)).c_str(), s->poll().reason.c_str());
        return 1;
    }
    const auto status = s->poll();

    const auto trajectory = cell.take_trajectory();
    std::vector<const abb::ProgramEvent*> cuts;
    for (const auto& e : program.events)
        if (e.kind == abb::EventKind::cut) cuts.push_back(&e);
    const PinTimes pins = avr ? avr_pin_times(*avr, t0, maps) : mock_pin_times(mock);
    std::vector<double> errors;
    for (const auto& t : pins.cutter_on) {
        if (errors.size() >= cuts.size()) break;
        const auto at = drivers::sim::sample_at(trajectory, t);
        if (at) errors.push_back((at->tcp_wobj_mm - cuts[errors.size()]->position_mm).norm());
    }
    // A fibre path's start: the robot arrives at its fibre_start (the event fires there and the
    // robot waits for the release) -> the board starts the thread feed.
    std::vector<double> to_feed_ms;
    std::size_t sample = 0, feed = 0;
    for (const auto& e : program.events) {
        if (e.kind != abb::EventKind::fibre_start) continue;
        while (sample < trajectory.size() && (trajectory[sample].tcp_wobj_mm - e.position_mm).norm() > 0.05)
            ++sample;
        if (sample == trajectory.size()) break;
        const SteadyTime arrived = trajectory[sample].wall;
        while (feed < pins.feed_start.size() && pins.feed_start[feed] < arrived) ++feed;
        if (feed == pins.feed_start.size()) break;
        to_feed_ms.push_back(std::chrono::duration<double, std::milli>(pins.feed_start[feed] - arrived).count());
    }
    std::printf("  printed in %.1f s real (%.1f s simulated)\n", wall, wall * scale);
    if (avr)
        std::printf("  gt2560-avr clock mapped %zu times, within %.2f ms\n", maps.size(), worst_half_rtt_ms);
    std::printf("  cut position error [mm] over %zu cuts: median %.4f  p99 %.4f  max %.4f"
                "  (target p99 <= 0.1 at time scale 1)\n",
                errors.size(), nearest_rank(errors, 0.5), nearest_rank(errors, 0.99),
                errors.empty() ? 0.0 : *std::max_element(errors.begin(), errors.end()));
    std::printf("  robot at a fibre path's start -> the board's thread feed starting [ms] over %zu paths: "
                "median %.2f  p99 %.2f  max %.2f\n",
                to_feed_ms.size(), nearest_rank(to_feed_ms, 0.5), nearest_rank(to_feed_ms, 0.99),
                to_feed_ms.empty() ? 0.0 : *std::max_element(to_feed_ms.begin(), to_feed_ms.end()));
    std::printf("  engine, counter change -> first command submitted [ms]:\n");
    for (const auto& t : status.sync.stats.timing)
        std::printf("    %-12s n=%-4zu median %.3f  p99 %.3f  max %.3f\n",
                    std::string(abb::to_string(t.kind)).c_str(), t.submit_ms.count, t.submit_ms.median,
                    t.submit_ms.p99, t.submit_ms.max);
    {
        std::lock_guard lock(mu);
        session = nullptr;
    }
    s.reset();
    robot.stop();
    board.deactivate();
    std::filesystem::remove_all(dir);
    return 0;
}
