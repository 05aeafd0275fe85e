// The planning pool: every task runs once, callers work on their own tasks while they wait (so a
// task may wait on tasks of its own), several callers share the threads, the first failure is
// rethrown and what had not begun is skipped, and the threads run at the nice value asked for. The
// planner's layer stage on the pool gives what it gives on one thread, and its progress sink is
// never called twice at once.
#include "daemon/jobs/thread_pool.hpp"

#include "job_test_files.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/plan/toolpaths_json.hpp"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace fibrecell;
using fibrecell::daemon::jobs::ThreadPool;
namespace fs = std::filesystem;

TEST(ThreadPool, RunsEveryTaskOnceAcrossItsThreadsAndTheCaller) {
    ThreadPool pool({.threads = 3});
    EXPECT_EQ(pool.threads(), 3u);
    std::vector<std::atomic<int>> runs(1000);
    std::mutex mu;
    std::set<std::thread::id> threads;
    pool.for_each(runs.size(), [&](std::size_t i) {
        ++runs[i];
        std::lock_guard lock(mu);
        threads.insert(std::this_thread::get_id());
    });
    for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
    EXPECT_GE(threads.size(), 1u);
    EXPECT_LE(threads.size(), 4u);  // the pool's three and the caller
    pool.for_each(0, [](std::size_t) { FAIL() << "no task to run"; });
}

TEST(ThreadPool, TasksMayWaitOnTasksOfTheirOwnAndCallersShareThePool) {
    ThreadPool pool({.threads = 2});
    std::atomic<int> inner{0};
    // Two planning workers at once, each with layers that split again: no deadlock, all done.
    std::vector<std::thread> workers;
    for (int w = 0; w < 2; ++w)
        workers.emplace_back([&] {
            pool.for_each(8, [&](std::size_t) { pool.for_each(16, [&](std::size_t) { ++inner; }); });
        });
    for (auto& t : workers) t.join();
    EXPECT_EQ(inner.load(), 2 * 8 * 16);
}

TEST(ThreadPool, TheFirstFailureIsRethrownAndTheRestSkipped) {
    ThreadPool pool({.threads = 2});
    // The thread that ran the failing task has recorded the failure before it claims again, so
    // it runs nothing more of the batch. (How much the other threads run in the meantime depends
    // on the scheduler, so that is not counted.)
    std::atomic<std::thread::id> thrower{};
    std::atomic<int> after_failure_on_thrower{0};
    try {
        pool.for_each(10000, [&](std::size_t i) {
            if (std::this_thread::get_id() == thrower.load()) ++after_failure_on_thrower;
            if (i == 3) {
                thrower = std::this_thread::get_id();
                throw std::runtime_error("layer 3: no outline");
            }
        });
        FAIL() << "expected the task's error";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "layer 3: no outline");
    }
    EXPECT_EQ(after_failure_on_thrower.load(), 0);
    // The pool goes on working after a failed batch.
    std::atomic<int> after{0};
    pool.for_each(100, [&](std::size_t) { ++after; });
    EXPECT_EQ(after.load(), 100);
}

TEST(ThreadPool, ItsThreadsRunAtTheNiceValueAskedFor) {
    const int own = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()));
    ThreadPool pool({.threads = 2, .nice = 12});
    std::mutex mu;
    std::set<int> nice_of_pool_threads;
    const auto caller = std::this_thread::get_id();
    pool.for_each(200, [&](std::size_t) {
        if (std::this_thread::get_id() == caller) return;
        const int n = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()));
        std::lock_guard lock(mu);
        nice_of_pool_threads.insert(n);
        std::this_thread::yield();
    });
    for (const int n : nice_of_pool_threads) EXPECT_EQ(n, std::max(own, 12));
    // The caller's own priority is left alone.
    EXPECT_EQ(::getpriority(PRIO_PROCESS, static_cast<id_t>(::gettid())), own);
}

TEST(ThreadPool, TheLayerStageOnThePoolMatchesOneThreadAndReportsOneCallAtATime) {
    // A 50 x 6 x 4 mm bar in tension: ten layers planned at once on four threads.
    const fibrecell::test::TempDir tmp("pool");
    const fs::path dir = tmp.path();
    const auto mesh = planner::structured_tet_mesh({.size = {50, 6, 4}, .cells = {25, 3, 5}});
    std::vector<planner::StressTensor> stress(mesh.tet_count(), planner::StressTensor::Zero());
    for (auto& s : stress) s(0, 0) = 30.0;
    fibrecell::test::write_vtk_file(dir / "bar.vtk", mesh, {.stress = &stress});
    std::ofstream(dir / "bar.job.yaml") << "name: bar\nmodel:\n  mesh: bar.vtk\n";
    const planner::JobSpec job = planner::load_job_file((dir / "bar.job.yaml").string());
    const planner::FieldStageResult field = fibrecell::test::field_stage_of(job);

    ThreadPool pool({.threads = 4});
    std::atomic<bool> in_sink{false};
    std::atomic<int> overlaps{0}, calls{0};
    const planner::StepControl control{[&](std::string_view, double) {
                                           if (in_sink.exchange(true)) ++overlaps;
                                           ++calls;
                                           std::this_thread::sleep_for(std::chrono::milliseconds(1));
                                           in_sink = false;
                                       },
                                       nullptr};
    const planner::LayerStageResult parallel =
        planner::run_layer_stage(job, field, {.executor = &pool}, control);
    const planner::LayerStageResult serial = planner::run_layer_stage(job, field);
    EXPECT_EQ(overlaps.load(), 0);
    EXPECT_GE(calls.load(), static_cast<int>(parallel.layers.size()));
    ASSERT_EQ(parallel.layers.size(), serial.layers.size());
    EXPECT_GE(parallel.layers.size(), 8u);
    EXPECT_EQ(planner::toolpaths_json_text("field", parallel.layers),
              planner::toolpaths_json_text("field", serial.layers));
}
