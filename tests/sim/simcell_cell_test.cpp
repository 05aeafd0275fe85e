// The simulated cell end to end through the real drivers: the RWS client and FcMainControl over
// loopback HTTP, RobotIoLink over loopback Modbus TCP, and chunks made by the real RAPID writer
// from a small print program, executed by the RAPID task on the motion simulator at a high time
// scale. Every assertion is about what the service would see (RWS values, Modbus events) or about
// the recorded trajectory against the programmed targets.
#include "drivers/sim/cell/sim_cell.hpp"

#include "drivers/abb/fcmain/fc_main_control.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"
#include "drivers/abb/rapid/reader.hpp"
#include "drivers/abb/rws/rws_client.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_simcell_cell_test {

using namespace std::chrono_literals;
using namespace fibrecell::drivers;
namespace rws = abb::rws;
namespace rapid = abb::rapid;
using abb::FcMainControl;
using abb::FcRunRequest;
using abb::FcState;
using abb::FcStatus;
using abb::RobotLayer;
using abb::RobotPath;
using Clock = std::chrono::steady_clock;
using fibrecell::test::eventually;

namespace {

// Simulated seconds per real second. FcMain's heartbeat timeout is at most 10 s simulated, i.e.
// 0.4 s of real time here (docs/simcell.md): enough margin for a loaded machine.
constexpr double scale = 25;

std::string fc_main_file() {
    return fibrecell::test::source_path("drivers/abb/rapid/FcMain.mod");
}

// A 20 mm PLA square, then a CCF layer with a 60 mm fibre: a head-switch barrier before each layer,
// a threading barrier at the fibre start, extrusion, cut and path-end events.
std::vector<RobotLayer> small_job() {
    RobotLayer pla{.index = 0, .z = 0.8, .nozzle = abb::Nozzle::pla};
    pla.paths.push_back(
        {true, {{140, 140}, {160, 140}, {160, 160}, {140, 160}}});
    RobotLayer ccf{.index = 1, .z = 0.85, .nozzle = abb::Nozzle::ccf};
    ccf.paths.push_back({false, {{120, 150}, {150, 150}, {180, 150}}});
    return {pla, ccf};
}

struct Job {
    abb::PrintProgram program;
    std::vector<abb::ChunkFile> chunks;  // exactly two
};

// The real writer, with the line limit lowered until the job takes two chunks.
Job two_chunk_job() {
    const abb::RobotCellConfig cell;
    Job job;
    job.program = abb::build_print_program(
        small_job(), cell, {.pla_speed_mm_s = 30, .ccf_speed_mm_s = 20, .pla_travel_speed_mm_s = 250, .ccf_travel_speed_mm_s = 250});
    for (int max_lines = 30; max_lines < 2000; max_lines += 5) {
        abb::RapidOutput out;
        try {
            out = abb::write_rapid_chunks(job.program, cell, {.max_lines = max_lines});
        } catch (const abb::RapidWriteError&) {
            continue;  // a stretch between stop points does not fit yet
        }
        if (out.modules.size() != 2) continue;
        for (const abb::RapidModule& m : out.modules) job.chunks.push_back({m.file_name, m.text});
        return job;
    }
    ADD_FAILURE() << "the writer never made two chunks";
    return job;
}

// The cell and the service's drivers connected to it.
struct Rig {
    sim::SimCell cell;
    rws::RwsClient rws;
    FcMainControl fc;
    abb::RobotIoLink io;

    explicit Rig(std::chrono::milliseconds service_watchdog = 0ms, double time_scale = scale)
        : cell({.time_scale = time_scale, .main_module = fc_main_file()}),
          rws({.host = "127.0.0.1", .port = cell.rws_port()}),
          fc(rws),
          io(io_config(cell.modbus_port(), service_watchdog)) {
        io.start();
    }

    static abb::RobotIoConfig io_config(int port, std::chrono::milliseconds watchdog) {
        abb::RobotIoConfig c;
        c.port = port;
        c.poll_period = 1000us;
        c.heartbeat_period = 20ms;  // several edges within FcMain's timeout at this time scale
        c.stable_reads = 1;
        c.reconnect_backoff_min = 20ms;
        c.reconnect_backoff_max = 100ms;
        c.service_watchdog = watchdog;
        c.stats_log_period = std::chrono::seconds(0);
        // These tests play a service that never resumes: a read a loaded machine answers late
        // (in a fresh clone's suite: none within 250 ms, the link back 49 ms later) must not
        // leave the robot paused for good. The pause on a fault is robot_io_test's.
        c.pause_on_fault = false;
        return c;
    }

    // Chunks uploaded, FcMain running with the service heartbeat seen, the run requested.
    // FcMain holds the robot after heartbeat_timeout_s without a service heartbeat: 3 s here,
    // since a busy machine stalled this test's Modbus link for a second once (in CI: no answer
    // within 250 ms, the link lost and back, the robot held before its first event). The test
    // of the hold gives its own.
    FcStatus start_run(const Job& job, double heartbeat_timeout_s = 3.0) {
        EXPECT_TRUE(io.wait_until_up(3000ms)) << io.snapshot().last_error;
        fc.upload_chunks("fibrecell/job", job.chunks);
        fc.ensure_running();
        // Handshake step 1 (docs/irc5-setup.md): FcMain's heartbeat toggles, so FcInit is done;
        // a request written before that is cleared unanswered as stale.
        EXPECT_TRUE(eventually([&] { return io.snapshot().robot_heartbeat_ok; }, 3000ms));
        return fc.request_run({.chunk_count = static_cast<int>(job.chunks.size()),
                               .heartbeat_timeout_s = heartbeat_timeout_s},
                              5000ms);
    }

};

// The service's part of a run as seen on Modbus: every accepted event value; each barrier the
// robot waits at is released (unless `hold` says to keep it) and recorded.
struct Service {
    Rig& rig;
    std::vector<std::uint16_t> events;
    std::vector<std::uint16_t> released;
    std::function<bool(std::uint16_t barrier)> hold = [](std::uint16_t) { return false; };

    void poll() {
        for (const abb::EventCounterChange& e : rig.io.take_events()) {
            events.push_back(e.value);
            if (e.value != 0 && e.barrier == e.value && !hold(e.value)) {
                rig.io.set_release(e.value);
                released.push_back(e.value);
            }
        }
    }

    // Serves until `done` holds; false on timeout.
    bool until(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
        return eventually([&] {
            poll();
            return done();
        }, timeout);
    }

    // What a failed wait saw, for the failure message.
    std::string describe() {
        std::ostringstream o;
        const FcStatus st = rig.fc.status();
        const sim::TaskStatus task = rig.cell.task_status();
        const sim::MotionStatus m = rig.cell.motion_status();
        const abb::RobotIoSnapshot io = rig.io.snapshot();
        o << "FcMain " << to_string(st.state) << " chunk " << st.chunk_now << " barrier "
          << st.barrier << " '" << st.message << "'; task state " << static_cast<int>(task.state)
          << " at " << task.module << ":" << task.line << " '" << task.error << "'; motion moving "
          << m.moving << " stopped " << m.stopped << " pending " << m.pending << " '" << m.error
          << "'; modbus " << to_string(io.state) << " event " << io.event_counter << " barrier "
          << io.barrier << " running " << io.running << " hb " << io.robot_heartbeat_ok
          << "; events seen";
        for (auto e : events) o << ' ' << e;
        o << "; released";
        for (auto b : released) o << ' ' << b;
        return o.str();
    }

    bool until_state(FcState s, std::chrono::milliseconds timeout) {
        return until([&] { return rig.fc.status().state == s; }, timeout);
    }
    bool until_event(std::uint16_t n, std::chrono::milliseconds timeout) {
        return until([&] { return !events.empty() && events.back() >= n; }, timeout);
    }
};

std::vector<int> barrier_numbers(const abb::PrintProgram& p) {
    std::vector<int> out;
    for (const abb::ProgramEvent& e : p.events)
        if (e.barrier) out.push_back(e.sequence);
    return out;
}

// The first event after the first barrier that drives the extruder while the robot prints.
int first_print_event(const abb::PrintProgram& p) {
    for (const abb::ProgramEvent& e : p.events)
        if (e.kind == abb::EventKind::extrude_on) return e.sequence;
    return 0;
}

// The robot stands still over `window_s` of the cell's simulated time (two samples of the motion
// thread, the second once the cell's clock has passed the window).
bool stands_still(sim::SimCell& cell, double window_s) {
    const sim::TrajectorySample a = cell.robot();
    const double until_s = cell.clock().now_s() + window_s;
    if (!eventually([&] { return cell.clock().now_s() >= until_s; })) return false;
    const sim::TrajectorySample b = cell.robot();
    return (a.tcp_base_mm - b.tcp_base_mm).norm() < 1e-9 && b.speed_mm_s == 0;
}

}  // namespace

TEST(SimCell, FcMainIsResidentAndStoppedAtMainAfterStartUp) {
    Rig r;
    const auto modules = r.rws.modules();
    ASSERT_EQ(modules.size(), 1u);
    EXPECT_EQ(modules[0].name, "FcMain");
    EXPECT_EQ(r.rws.execution_state().state, rws::ExecutionState::stopped);
    EXPECT_EQ(r.rws.controller_state(), rws::ControllerState::motoron);
    EXPECT_TRUE(r.cell.controller().program_pointer_at_main());
    EXPECT_EQ(r.rws.download_file("fibrecell/FcMain.mod").substr(0, 13), "MODULE FcMain");
    EXPECT_EQ(r.fc.status().state, FcState::idle);
}

TEST(SimCell, HeartbeatTimeoutIsScaledToSimulatedTimeAndReadBackInRealTime) {
    Rig r;
    // FcMain's default 1 s, as the task counts it: 1 s of real time at the cell's time scale.
    EXPECT_EQ(r.cell.task().read_data("FcMain", "nFcHbTimeout").num(), scale);
    EXPECT_EQ(r.rws.symbol("FcMain", "nFcHbTimeout"), "1");
    r.rws.request_mastership();
    r.rws.set_symbol("FcMain", "nFcHbTimeout", "0.5");
    r.rws.release_mastership();
    EXPECT_EQ(r.cell.task().read_data("FcMain", "nFcHbTimeout").num(), 0.5 * scale);
    EXPECT_EQ(r.rws.symbol("FcMain", "nFcHbTimeout"), "0.5");
}

TEST(SimCell, EnsureRunningStartsFcMainAndItsHeartbeatReachesModbus) {
    Rig r;
    ASSERT_TRUE(r.io.wait_until_up(3000ms)) << r.io.snapshot().last_error;
    r.fc.ensure_running();
    EXPECT_EQ(r.rws.execution_state().state, rws::ExecutionState::running);
    EXPECT_EQ(r.cell.task_status().state, sim::TaskState::running);
    EXPECT_TRUE(eventually([&] { return r.io.snapshot().robot_heartbeat_ok; }, 3000ms));
    EXPECT_FALSE(r.io.snapshot().running);  // no run yet: doFcRunning low
    // A second call finds it running and changes nothing.
    r.fc.ensure_running();
    EXPECT_EQ(r.cell.controller().start_count(), 1);
}

TEST(SimCell, TwoChunkRunDeliversEveryEventInOrderOverModbus) {
    const Job job = two_chunk_job();
    ASSERT_EQ(job.chunks.size(), 2u);
    Rig r;
    const FcStatus started = r.start_run(job);
    EXPECT_EQ(started.state, FcState::running);
    Service s{r};
    ASSERT_TRUE(s.until_state(FcState::completed, 20000ms)) << s.describe();
    s.poll();

    const int n = static_cast<int>(job.program.events.size());
    ASSERT_GT(n, 5);
    // The robot set the event group to 0 at the start, then to 1..N, each once, in order.
    std::vector<int> written;
    for (const sim::SignalWrite& w : r.cell.output_history())
        if (w.signal == "goFcEvent" && w.value != 0) written.push_back(static_cast<int>(w.value));
    std::vector<int> expected(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) expected[static_cast<std::size_t>(i)] = i + 1;
    EXPECT_EQ(written, expected);
    // Modbus shows them in order (several may pass between two polls), ending at N.
    ASSERT_FALSE(s.events.empty());
    EXPECT_TRUE(std::is_sorted(s.events.begin(), s.events.end()));
    EXPECT_EQ(std::adjacent_find(s.events.begin(), s.events.end()), s.events.end());
    EXPECT_EQ(s.events.back(), n);
    // Every barrier was seen and released, in order.
    const std::vector<int> barriers = barrier_numbers(job.program);
    EXPECT_EQ(std::vector<int>(s.released.begin(), s.released.end()), barriers);

    std::cout << "two-chunk run: " << n << " events (" << s.events.size() << " seen on Modbus), "
              << barriers.size() << " barriers, " << job.chunks[0].text.size() << " + "
              << job.chunks[1].text.size()
              << " bytes of chunks, robot at t = " << r.cell.robot().t_s << " s simulated\n";
    const FcStatus done = r.fc.status();
    EXPECT_EQ(done.chunk_done, 2);
    EXPECT_EQ(done.chunk_now, 0);
    EXPECT_FALSE(r.io.snapshot().running);
    EXPECT_EQ(r.rws.execution_state().state, rws::ExecutionState::running);  // FcMain waits again
}

TEST(SimCell, BarrierHoldsTheRobotUntilTheServiceReleasesIt) {
    const Job job = two_chunk_job();
    const std::vector<int> barriers = barrier_numbers(job.program);
    ASSERT_GE(barriers.size(), 2u);
    const auto held = static_cast<std::uint16_t>(barriers[1]);  // the threading barrier, mid-job
    Rig r;
    r.start_run(job);
    Service s{r};
    s.hold = [&](std::uint16_t b) { return b == held; };
    ASSERT_TRUE(s.until_event(held, 20000ms)) << s.describe();
    EXPECT_EQ(s.events.back(), held);
    // The link publishes its snapshot just after it hands out the change.
    EXPECT_TRUE(s.until([&] { return r.io.snapshot().barrier == held; }, 1000ms));
    EXPECT_EQ(r.fc.status().barrier, held);
    // Held: standing, and nothing further happens for 4 simulated s.
    EXPECT_TRUE(stands_still(r.cell, 4.0));
    s.poll();
    EXPECT_EQ(s.events.back(), held);
    EXPECT_EQ(r.fc.status().state, FcState::running);

    r.io.set_release(held);
    ASSERT_TRUE(s.until_event(static_cast<std::uint16_t>(held + 1), 5000ms)) << s.describe();
    ASSERT_TRUE(s.until_state(FcState::completed, 20000ms)) << s.describe();
}

TEST(SimCell, PauseStopsTheRobotOnItsPathAndResumeGoesOn) {
    const Job job = two_chunk_job();
    Rig r;
    r.start_run(job);
    Service s{r};
    const auto printing = static_cast<std::uint16_t>(first_print_event(job.program));
    ASSERT_GT(printing, 0);
    ASSERT_TRUE(s.until_event(printing, 20000ms)) << s.describe();

    r.io.set_pause(true);
    ASSERT_TRUE(s.until_state(FcState::paused, 3000ms));
    ASSERT_TRUE(eventually([&] { return r.cell.robot().speed_mm_s == 0; }, 3000ms));
    const sim::TrajectorySample stopped = r.cell.robot();
    EXPECT_TRUE(stands_still(r.cell, 4.0));
    s.poll();
    const std::uint16_t seen = s.events.back();

    r.io.set_pause(false);
    ASSERT_TRUE(s.until_state(FcState::running, 3000ms));
    ASSERT_TRUE(
        eventually([&] { return r.cell.robot().path_mm > stopped.path_mm + 1.0; }, 3000ms));
    ASSERT_TRUE(s.until_state(FcState::completed, 20000ms)) << s.describe();
    EXPECT_GT(s.events.back(), seen);

    // The trajectory stood at the pause position and went on from there along the same path.
    // (The last samples of the deceleration reach that position to within 1e-6 mm while still
    // moving a little: the one that stands is what counts.)
    const std::vector<sim::TrajectorySample> t = r.cell.take_trajectory();
    const auto at_stop = std::find_if(t.begin(), t.end(), [&](const sim::TrajectorySample& x) {
        return (x.tcp_base_mm - stopped.tcp_base_mm).norm() < 1e-6 && x.speed_mm_s == 0;
    });
    EXPECT_NE(at_stop, t.end()) << "no sample stands at the pause position";
}

TEST(SimCell, AbortEndsTheRunWhereTheRobotStands) {
    const Job job = two_chunk_job();
    Rig r;
    r.start_run(job);
    Service s{r};
    const auto printing = static_cast<std::uint16_t>(first_print_event(job.program));
    ASSERT_TRUE(s.until_event(printing, 20000ms)) << s.describe();

    r.io.set_abort(true);
    ASSERT_TRUE(s.until_state(FcState::aborted, 3000ms));
    ASSERT_TRUE(eventually([&] { return !r.io.snapshot().running; }, 3000ms));
    EXPECT_TRUE(eventually([&] { return r.cell.motion_status().pending == 0; }, 3000ms));
    EXPECT_TRUE(stands_still(r.cell, 2.5));
    const FcStatus st = r.fc.status();
    EXPECT_EQ(st.message, "aborted by the service");
    EXPECT_LT(st.chunk_done, 2);
    r.io.set_abort(false);
    // FcMain went back to waiting for a run; the robot stays where it stopped.
    EXPECT_EQ(r.rws.execution_state().state, rws::ExecutionState::running);
    s.poll();
    EXPECT_LT(s.events.back(), job.program.events.size());
}

TEST(SimCell, LostServiceHeartbeatHoldsTheRobot) {
    const Job job = two_chunk_job();
    // heartbeat_out toggles only while the service loop reports alive; at time scale 20 FcMain's
    // timeout can be 0.5 s of real time.
    Rig r(40ms, 20);
    std::atomic<bool> alive{true};
    std::thread service_loop([&] {
        while (alive) {
            r.io.service_alive();
            std::this_thread::sleep_for(5ms);
        }
    });
    r.start_run(job, 0.5);  // FcMain holds after 0.5 s of real time without an edge
    Service s{r};
    const auto printing = static_cast<std::uint16_t>(first_print_event(job.program));
    const bool printed = s.until_event(printing, 20000ms);
    // The service loop stops: no more heartbeat edges after its watchdog.
    const auto quiet = Clock::now();
    alive = false;
    service_loop.join();
    ASSERT_TRUE(printed) << s.describe();
    ASSERT_TRUE(eventually([&] { return r.fc.status().state == FcState::held; }, 3000ms));
    EXPECT_GE(Clock::now() - quiet, 400ms);  // not before the timeout
    EXPECT_TRUE(eventually([&] { return !r.io.snapshot().running; }, 2000ms));
    EXPECT_TRUE(eventually([&] { return r.cell.robot().speed_mm_s == 0; }, 2000ms));
    EXPECT_TRUE(stands_still(r.cell, 2.5));
    EXPECT_TRUE(r.cell.wait_for_log("service heartbeat lost", 1000ms));
    EXPECT_EQ(r.fc.status().message, "heartbeat lost: held, waiting for resume or abort");
}

TEST(SimCell, DroppedModbusLinkIsAFaultOfTheServiceLink) {
    Rig r;
    ASSERT_TRUE(r.io.wait_until_up(3000ms));
    r.fc.ensure_running();
    ASSERT_TRUE(eventually([&] { return r.io.snapshot().robot_heartbeat_ok; }, 3000ms));

    r.cell.drop_modbus_link(1000ms);  // long enough for a reconnect attempt on a loaded machine
    ASSERT_TRUE(eventually([&] { return r.io.state() == abb::RobotIoState::fault; }));
    const abb::RobotIoSnapshot down = r.io.snapshot();
    EXPECT_NE(down.fault_reason.find("modbus 127.0.0.1:" + std::to_string(r.cell.modbus_port())),
              std::string::npos)
        << down.fault_reason;
    // Refused for a while (a reconnect attempt is turned away), then the link comes back by
    // itself.
    const auto refused = down.stats.connect_failures;
    ASSERT_TRUE(eventually([&] { return r.io.snapshot().stats.connect_failures > refused; }))
        << r.io.snapshot().last_error << " failures " << refused;
    EXPECT_EQ(r.io.state(), abb::RobotIoState::fault);
    EXPECT_TRUE(r.io.wait_until_up(10s)) << r.io.snapshot().last_error;
}

TEST(SimCell, UnreachableTargetStopsTheTaskWithAClearErrorOverRws) {
    Job job = two_chunk_job();
    // Move the first linear target of chunk 1 two metres out.
    std::string& text = job.chunks[0].text;
    const std::size_t move = text.find("MoveL [[");
    ASSERT_NE(move, std::string::npos);
    const std::size_t x_end = text.find(',', move);
    text.replace(move + 8, x_end - move - 8, "2400");
    const auto line = static_cast<std::size_t>(
        std::count(text.begin(), text.begin() + static_cast<long>(move), '\n') + 1);

    Rig r;
    r.start_run(job);
    Service s{r};
    ASSERT_TRUE(s.until(
        [&] { return r.rws.execution_state().state == rws::ExecutionState::stopped; }, 20000ms))
        << s.describe();
    const std::vector<rws::BuildError> log = r.rws.build_errors();
    ASSERT_EQ(log.size(), 1u);
    EXPECT_EQ(log[0].module, "FcChunk0001");
    EXPECT_EQ(log[0].row, line);
    EXPECT_NE(log[0].message.find("unreachable"), std::string::npos) << log[0].message;
    std::cout << "over RWS: " << rws::format(log[0]) << "\n";
    EXPECT_EQ(r.cell.task_status().state, sim::TaskState::error);
    EXPECT_TRUE(
        r.cell.wait_for_log("RAPID task error: FcChunk0001 line " + std::to_string(line), 1000ms));
    // Recovery as on the real controller: PP to main clears it, FcMain runs again.
    r.fc.ensure_running();
    EXPECT_TRUE(r.rws.build_errors().empty());
    EXPECT_TRUE(eventually(
        [&] { return r.fc.status().message == "run interrupted by a program reset"; }, 2000ms))
        << r.fc.status().message;
}

TEST(SimCell, MotorsOffRefusesStartUntilMotorsOn) {
    Rig r;
    r.cell.motors_off();
    EXPECT_EQ(r.rws.controller_state(), rws::ControllerState::motoroff);
    try {
        r.fc.ensure_running();
        FAIL() << "expected FcRunError";
    } catch (const abb::FcRunError& e) {
        EXPECT_NE(std::string(e.what()).find("motoroff"), std::string::npos) << e.what();
    }
    try {
        r.rws.start_execution();
        FAIL() << "expected RwsError";
    } catch (const rws::RwsError& e) {
        EXPECT_NE(std::string(e.what()).find("motors are not on"), std::string::npos) << e.what();
    }
    EXPECT_EQ(r.rws.execution_state().state, rws::ExecutionState::stopped);
    r.cell.motors_on();
    r.fc.ensure_running();
    EXPECT_EQ(r.rws.execution_state().state, rws::ExecutionState::running);
}

TEST(SimCell, MotorsOffDuringARunStopsTheRobotAndRapid) {
    const Job job = two_chunk_job();
    Rig r;
    r.start_run(job);
    Service s{r};
    ASSERT_TRUE(s.until_event(static_cast<std::uint16_t>(first_print_event(job.program)), 20000ms))
        << s.describe();
    r.cell.motors_off();
    EXPECT_TRUE(stands_still(r.cell, 1.25));
    EXPECT_TRUE(eventually(
        [&] { return r.rws.execution_state().state == rws::ExecutionState::stopped; }, 2000ms));
    EXPECT_EQ(r.cell.motion_status().pending, 0u);
}

TEST(SimCell, StopWithErrorStopsRapidAndReportsTheError) {
    Rig r;
    ASSERT_TRUE(r.io.wait_until_up(3000ms));
    r.fc.ensure_running();
    // FcMain executing: its heartbeat is on Modbus.
    ASSERT_TRUE(eventually([&] { return r.io.snapshot().robot_heartbeat_ok; }, 3000ms));
    r.cell.stop_with_error("50204 Motion supervision");
    EXPECT_TRUE(eventually(
        [&] { return r.rws.execution_state().state == rws::ExecutionState::stopped; }, 2000ms));
    const std::vector<rws::BuildError> log = r.rws.build_errors();
    ASSERT_FALSE(log.empty());
    EXPECT_EQ(log.back().message, "50204 Motion supervision");
    EXPECT_EQ(r.cell.task_status().state, sim::TaskState::error);
    r.fc.ensure_running();  // PP to main and start, as the service recovers
    EXPECT_EQ(r.rws.execution_state().state, rws::ExecutionState::running);
    EXPECT_TRUE(r.rws.build_errors().empty());
}

TEST(SimCell, TrajectoryPassesEveryProgrammedTargetExactly) {
    const Job job = two_chunk_job();
    // Every target of both chunks, in order, as the reader reads it back.
    std::vector<Eigen::Vector3d> targets;
    for (const abb::ChunkFile& c : job.chunks) {
        rapid::ValidateOptions o;
        o.file_name = c.file_name;
        o.known_signals = abb::RobotSignals{}.all();
        o.external_routines = {"FcBarrier"};
        const rapid::CheckResult read = rapid::check_module(c.text, o);
        ASSERT_TRUE(read.ok()) << c.file_name;
        for (const rapid::MoveTarget& t : rapid::move_targets(*read.module)) {
            ASSERT_TRUE(t.robtarget) << t.line;
            targets.push_back(t.robtarget->trans_mm);
        }
    }
    ASSERT_GT(targets.size(), 10u);
    Rig r;
    r.cell.take_trajectory();  // nothing before the run
    r.start_run(job);
    Service s{r};
    ASSERT_TRUE(s.until_state(FcState::completed, 20000ms)) << s.describe();
    const std::vector<sim::TrajectorySample> t = r.cell.take_trajectory();
    ASSERT_FALSE(t.empty());
    // Samples at every segment end: each target is passed exactly, in program order.
    std::size_t at = 0;
    for (std::size_t k = 0; k < targets.size(); ++k) {
        while (at < t.size() && (t[at].tcp_wobj_mm - targets[k]).norm() > 1e-6) ++at;
        ASSERT_LT(at, t.size()) << "target " << k << " (" << targets[k].transpose()
                                << ") never reached";
    }
    EXPECT_LT((t.back().tcp_wobj_mm - targets.back()).norm(), 1e-6);
    EXPECT_EQ(t.back().speed_mm_s, 0);
    // Timestamps: simulated and wall time agree through the cell's clock.
    for (std::size_t i = 1; i < t.size(); ++i) ASSERT_GE(t[i].t_s, t[i - 1].t_s);
    EXPECT_NEAR(r.cell.clock().sim_at(t.back().wall), t.back().t_s, 1e-6);
}

TEST(SimCell, LoadingAModuleWhileRapidRunsIsRefused) {
    Rig r;
    r.fc.ensure_running();
    r.rws.upload_file("fibrecell/FcMain.mod", r.rws.download_file("fibrecell/FcMain.mod"));
    r.rws.request_mastership();
    try {
        r.rws.load_module("fibrecell/FcMain.mod", true);
        FAIL() << "expected RwsError";
    } catch (const rws::RwsError& e) {
        EXPECT_NE(std::string(e.what()).find("while RAPID is running"), std::string::npos)
            << e.what();
    }
    r.rws.release_mastership();
    EXPECT_EQ(r.rws.execution_state().state, rws::ExecutionState::running);
}

}  // namespace sim_simcell_cell_test
