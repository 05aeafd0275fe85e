// The real resident main module FcMain.mod running in the simulated RAPID task with two chunk
// modules made by the real chunk writer, against a small signal map standing in for the I/O
// coupler and a test thread playing the service: the heartbeat, the run request over FcMain's
// PERS, barrier releases. Checked: the events come out in order on goFcEvent, a barrier holds the
// robot until its release, the pause request stops the motion and its drop resumes it, heartbeat
// loss holds the run (motion stopped, doFcRunning low) until the resume handshake.
#include "drivers/sim/rapid_exec/rapid_task.hpp"

#include "drivers/abb/rapid/rapid_writer.hpp"
#include "drivers/abb/rapid/reader.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_rapid_task_fcmain_test {

using namespace fibrecell;
using namespace fibrecell::drivers;
using namespace fibrecell::drivers::sim;
using namespace std::chrono_literals;
using fibrecell::test::eventually;

namespace {

constexpr double scale = 50;  // simulated seconds per real second
const abb::RobotCellConfig cell;
const std::string fc_main_path = fibrecell::test::source_path("drivers/abb/rapid/FcMain.mod");
const std::string job_dir = "HOME:/fibrecell/job";

// The 1-based line of FcMain.mod that contains `text`.
std::size_t fc_main_line(const std::string& text) {
    std::ifstream in(fc_main_path);
    std::string line;
    for (std::size_t n = 1; std::getline(in, line); ++n)
        if (line.find(text) != std::string::npos) return n;
    ADD_FAILURE() << "FcMain.mod has no line with " << text;
    return 0;
}

// A 20 mm PLA square, then a CCF layer with a 60 mm fibre, written as exactly two chunks.
struct Job {
    abb::PrintProgram program;
    std::vector<abb::RapidModule> chunks;
    std::vector<int> barriers;  // sequence numbers of the barrier events, in order
};

Job two_chunk_job() {
    abb::RobotLayer pla{.index = 0, .z = 0.8, .nozzle = abb::Nozzle::pla};
    pla.paths.push_back(
        {true, {{140, 140}, {160, 140}, {160, 160}, {140, 160}}});
    abb::RobotLayer ccf{.index = 1, .z = 0.85, .nozzle = abb::Nozzle::ccf};
    ccf.paths.push_back({false, {{120, 150}, {150, 150}, {180, 150}}});
    Job job;
    job.program = abb::build_print_program(
        {pla, ccf}, cell, {.pla_speed_mm_s = 30, .ccf_speed_mm_s = 20, .pla_travel_speed_mm_s = 250, .ccf_travel_speed_mm_s = 250});
    for (const abb::ProgramEvent& e : job.program.events)
        if (e.barrier) job.barriers.push_back(e.sequence);
    for (int max_lines = 30; max_lines < 2000; max_lines += 5) {
        try {
            auto out = abb::write_rapid_chunks(job.program, cell, {.max_lines = max_lines});
            if (out.modules.size() != 2) continue;
            job.chunks = out.modules;
            return job;
        } catch (const abb::RapidWriteError&) {
            // a stretch between stop points does not fit yet
        }
    }
    ADD_FAILURE() << "the writer never made two chunks";
    return job;
}

class FcMainTask : public ::testing::Test {
  protected:
    SimClock clock{scale};
    // Joints 0, as the writer assumes; a coarse tick keeps the motion thread light (the trigger
    // positions are checked in rapid_task_motion_test).
    MotionSimulator motion{clock, {.solver = cell.solver, .tick_s = 0.005, .record_period_s = 0.05}};
    std::mutex mu;
    std::map<std::string, double> values;
    std::vector<double> events;    // every write of goFcEvent, in order
    std::vector<double> barriers;  // every write of goFcBarrier
    std::map<std::string, std::string> files;
    std::vector<std::string> log;
    RapidTask task{clock, motion, io()};
    const Job job = two_chunk_job();
    const std::size_t wait_run_line = fc_main_line("WaitUntil bFcRun");
    const std::size_t barrier_line = fc_main_line("WaitUntil \\InPos, GInput(giFcRelease)");

    std::atomic<bool> beating{true};
    std::atomic<bool> quit{false};
    std::thread heartbeat;

    FcMainTask() {
        for (const std::string& s : cell.signals.all()) values[s] = 0;
        for (const abb::RapidModule& m : job.chunks) files[job_dir + "/" + m.file_name] = m.text;
    }
    ~FcMainTask() override {
        quit = true;
        if (heartbeat.joinable()) heartbeat.join();
    }

    TaskIo io() {
        return {.read_signal =
                    [this](const std::string& s) {
                        const std::lock_guard g(mu);
                        return values.at(s);
                    },
                .write_signal =
                    [this](const std::string& s, double v) {
                        const std::lock_guard g(mu);
                        values.at(s) = v;
                        if (s == cell.signals.event) events.push_back(v);
                        if (s == cell.signals.barrier) barriers.push_back(v);
                    },
                .read_file =
                    [this](const std::string& path) -> std::optional<std::string> {
                        const std::lock_guard g(mu);
                        auto it = files.find(path);
                        if (it == files.end()) return std::nullopt;
                        return it->second;
                    },
                .log =
                    [this](const std::string& text) {
                        const std::lock_guard g(mu);
                        log.push_back(text);
                    },
                .known_signals = cell.signals.all()};
    }
    void set_input(const std::string& s, double v) {
        {
            const std::lock_guard g(mu);
            values.at(s) = v;
        }
        task.signal_changed(s, v);
    }
    double value(const std::string& s) {
        const std::lock_guard g(mu);
        return values.at(s);
    }
    std::vector<double> written_events() {
        const std::lock_guard g(mu);
        return events;
    }
    bool barrier_written(int b) {
        const std::lock_guard g(mu);
        return std::find(barriers.begin(), barriers.end(), b) != barriers.end();
    }
    double num(const std::string& name) { return task.read_data("FcMain", name).num(); }

    // The service's side: heartbeat every 0.1 s (simulated), FcMain loaded and started, the job
    // parameters written and the run requested once FcMain waits for it.
    // hb_timeout_s: FcMain's heartbeat timeout; generous unless the test is about the heartbeat,
    // so that a test thread held up on a loaded machine does not look like a lost service.
    void start_run(double hb_timeout_s = 10) {
        heartbeat = std::thread([this] {
            double next = clock.now_s();
            double level = 0;
            while (!quit) {
                if (beating) {
                    level = 1 - level;
                    set_input(cell.signals.heartbeat_in, level);
                }
                next += 0.1;
                clock.sleep_until(next);
            }
        });
        abb::rapid::ValidateOptions o;
        o.known_signals = cell.signals.all();
        task.load(abb::rapid::read_module_file(fc_main_path, o));
        task.reset_pp();
        task.start();
        ASSERT_TRUE(eventually([&] { return task.status().line == wait_run_line; }));
        task.write_data("FcMain", "sFcJobDir", abb::rapid::string_value(job_dir));
        task.write_data("FcMain", "nFcChunkCount", abb::rapid::num_value(2));
        task.write_data("FcMain", "nFcFirstChunk", abb::rapid::num_value(1));
        task.write_data("FcMain", "nFcHbTimeout", abb::rapid::num_value(hb_timeout_s));
        task.write_data("FcMain", "bFcRun", abb::rapid::bool_value(true));
        ASSERT_TRUE(eventually([&] { return num("nFcState") == 1; })) << task.status().error;
    }

    // Waits for barrier `b`, checks that the robot stays at it for 0.3 s (simulated) with no
    // later event, then releases it.
    void release(int b) {
        ASSERT_TRUE(eventually([&] { return barrier_written(b); }, 10s))
            << "barrier " << b << "; task: " << task.status().error;
        clock.sleep_until(clock.now_s() + 0.3);
        EXPECT_EQ(written_events().back(), b);
        // The program pointer is in FcBarrier's wait (a TRAP may be running just now).
        EXPECT_TRUE(eventually([&] {
            const TaskStatus s = task.status();
            return s.module == "FcMain" && s.line == barrier_line;
        }));
        EXPECT_EQ(num("nFcBarrier"), b);
        EXPECT_TRUE(motion.in_position());
        set_input(cell.signals.release, b);
    }

    void finish_run(std::size_t from_barrier) {
        for (std::size_t i = from_barrier; i < job.barriers.size(); ++i) release(job.barriers[i]);
        ASSERT_TRUE(eventually([&] { return num("nFcState") == 4; }, 10s))
            << "state " << num("nFcState") << ", task: " << task.status().error;
        // 0 from the start of the run, then every event number once, in order.
        std::vector<double> expected{0};
        for (const abb::ProgramEvent& e : job.program.events) expected.push_back(e.sequence);
        EXPECT_EQ(written_events(), expected);
        EXPECT_EQ(num("nFcChunkDone"), 2);
        EXPECT_EQ(value(cell.signals.running), 0);
        EXPECT_EQ(task.status().loaded, std::vector<std::string>{"FcMain"});
        EXPECT_EQ(task.status().state, TaskState::running);  // back to waiting for a run
    }
};

}  // namespace

TEST_F(FcMainTask, RunsTwoChunksWithEventsInOrderAndBarriersHeld) {
    ASSERT_EQ(job.chunks.size(), 2u);
    ASSERT_GE(job.barriers.size(), 2u);
    const double t0 = clock.now_s();
    start_run();
    EXPECT_EQ(value(cell.signals.running), 1);
    finish_run(0);
    RecordProperty("simulated_run_s", std::to_string(clock.now_s() - t0));
}

TEST_F(FcMainTask, PauseRequestStopsTheMotionAndItsDropResumes) {
    start_run();
    release(job.barriers[0]);
    ASSERT_TRUE(eventually([&] { return motion.status().moving; }));
    set_input(cell.signals.pause, 1);
    ASSERT_TRUE(eventually([&] { return num("nFcState") == 2; }));
    ASSERT_TRUE(eventually([&] { return motion.current().speed_mm_s == 0; }));
    EXPECT_TRUE(motion.status().stopped);
    const double path = motion.current().path_mm;
    clock.sleep_until(clock.now_s() + 0.5);
    EXPECT_EQ(motion.current().path_mm, path);
    EXPECT_EQ(value(cell.signals.running), 1);  // a pause is not a hold
    set_input(cell.signals.pause, 0);
    ASSERT_TRUE(eventually([&] { return num("nFcState") == 1; }));
    EXPECT_FALSE(motion.status().stopped);
    finish_run(1);
}

TEST_F(FcMainTask, HeartbeatLossHoldsTheRunUntilResumed) {
    start_run(6);
    release(job.barriers[0]);
    ASSERT_TRUE(eventually([&] { return motion.status().moving; }));
    beating = false;
    // Held within the timeout (6 s: 120 ms of real time, margin for a loaded machine) and a tick.
    ASSERT_TRUE(eventually([&] { return num("nFcState") == 3; }));
    EXPECT_EQ(value(cell.signals.running), 0);
    EXPECT_TRUE(motion.status().stopped);
    EXPECT_EQ(task.read_data("FcMain", "sFcMessage").string(),
              "heartbeat lost: held, waiting for resume or abort");
    ASSERT_TRUE(eventually([&] { return motion.current().speed_mm_s == 0; }));
    const double path = motion.current().path_mm;
    clock.sleep_until(clock.now_s() + 0.5);
    EXPECT_EQ(motion.current().path_mm, path);
    // Resume: heartbeat back, then the pause request rises and drops.
    beating = true;
    clock.sleep_until(clock.now_s() + 0.3);
    set_input(cell.signals.pause, 1);
    clock.sleep_until(clock.now_s() + 0.3);
    EXPECT_EQ(num("nFcState"), 3);
    set_input(cell.signals.pause, 0);
    ASSERT_TRUE(eventually([&] { return num("nFcState") == 1; }));
    EXPECT_EQ(value(cell.signals.running), 1);
    finish_run(1);
}

TEST_F(FcMainTask, AbortStopsClearsThePathAndReturnsToIdle) {
    start_run();
    release(job.barriers[0]);
    ASSERT_TRUE(eventually([&] { return motion.status().moving; }));
    set_input(cell.signals.abort, 1);
    // FcAbort: StopMove, ClearPath, StartMove, ExitCycle; FcInit unloads the chunks.
    ASSERT_TRUE(eventually([&] { return task.status().line == wait_run_line; }));
    EXPECT_EQ(num("nFcState"), 5);
    EXPECT_EQ(task.read_data("FcMain", "sFcMessage").string(), "aborted by the service");
    EXPECT_EQ(num("nFcChunkNow"), 1);
    EXPECT_EQ(value(cell.signals.running), 0);
    EXPECT_EQ(task.status().loaded, std::vector<std::string>{"FcMain"});
    ASSERT_TRUE(eventually([&] { return !motion.status().moving; }));
    EXPECT_EQ(motion.status().pending, 0u);
    EXPECT_FALSE(motion.status().stopped);
    EXPECT_LT(written_events().back(), job.program.events.back().sequence);  // the rest never came
    EXPECT_EQ(task.status().state, TaskState::running);
}

}  // namespace sim_rapid_task_fcmain_test
