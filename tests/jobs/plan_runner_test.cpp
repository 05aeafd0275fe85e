// Planning workers on a real job store: a submitted job is planned with progress, a job that
// cannot be planned fails with its reason while another plans fine, abort cancels a running or a
// queued plan, and a shutdown leaves the job to be planned again after the restart.
#include "daemon/jobs/plan_runner.hpp"

#include "job_test_files.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <future>
#include <mutex>
#include <set>
#include <sstream>

using namespace fibrecell;
using namespace fibrecell::daemon::jobs;
using fibrecell::test::read_file;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

class PlanRunnerTest : public ::testing::Test {
  protected:
    void SetUp() override {
        // The bar, and the same mesh without stress, which cannot be planned.
        test::write_tension_bar(dir_ / "bar.vtk");
        test::write_tension_bar(dir_ / "bare.vtk", false);
        bar_.job_yaml = "name: bar\nmodel:\n  mesh: bar.vtk\n";
        bar_.files = {{"bar.vtk", read_file(dir_ / "bar.vtk")}};
        broken_.job_yaml = "name: broken\nmodel:\n  mesh: bare.vtk\n";
        broken_.files = {{"bare.vtk", read_file(dir_ / "bare.vtk")}};
    }

    JobStoreOptions options() const { return {.state_dir = dir_ / "state"}; }
    PlanRunnerOptions runner_options(int workers) const {
        PlanRunnerOptions o;
        o.workers = workers;
        return o;
    }

    test::TempDir dir_{"planrunner"};
    JobInput bar_, broken_;
};

}  // namespace

TEST_F(PlanRunnerTest, PlansASubmittedJobWithProgress) {
    JobStore store(options());
    store.load_all();
    PlanRunner runner(store, runner_options(1));
    std::mutex mu;
    std::vector<std::string> stages;
    std::vector<JobRecord> finished;
    std::set<int> nice;  // of the threads that reported progress
    runner.on_progress([&](std::int64_t id, const JobProgress& p) {
        const int thread_nice = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()));
        std::lock_guard lock(mu);
        nice.insert(thread_nice);
        EXPECT_EQ(id, 1);
        EXPECT_GE(p.fraction, 0.0);
        EXPECT_LE(p.fraction, 1.0);
        if (stages.empty() || stages.back() != p.stage) stages.push_back(p.stage);
    });
    runner.on_finished([&](const JobRecord& r) {
        std::lock_guard lock(mu);
        finished.push_back(r);
    });
    runner.enqueue(store.submit(bar_).id);
    runner.wait_idle();
    const JobRecord r = store.get(1);
    EXPECT_EQ(r.state, JobState::planned);
    EXPECT_EQ(r.plan_attempts, 1);
    EXPECT_TRUE(r.progress.stage.empty());
    EXPECT_TRUE(fs::exists(store.plan_dir(1) / "report.json"));
    EXPECT_TRUE(fs::exists(store.plan_dir(1) / "rapid" / "FcChunk0001.mod"));
    std::lock_guard lock(mu);
    ASSERT_GE(stages.size(), 4u);
    EXPECT_EQ(stages.front(), "read");
    EXPECT_EQ(stages.back(), "robot");
    ASSERT_EQ(finished.size(), 1u);
    EXPECT_EQ(finished[0].state, JobState::planned);
    // Planning runs below the service's priority (a print's sync threads come first).
    ASSERT_FALSE(nice.empty());
    EXPECT_GE(*nice.begin(), 10);
}

// The service reads a job once, at its submission: the typed job and the print's settings made
// then are what it plans, not the stored file read again (which the test spoils to tell).
TEST_F(PlanRunnerTest, AJobIsReadOnceAtItsSubmissionAndPlannedAsReadThen) {
    int settings_made = 0;
    JobStoreOptions o = options();
    o.settings_for = [&](const planner::JobSpec& job) {
        ++settings_made;
        return daemon::print::print_settings(job, daemon::CellConfig{});
    };
    JobStore store(o);
    store.load_all();
    PlanRunner runner(store, runner_options(1));
    const std::int64_t id = store.submit(bar_).id;
    std::ofstream(store.input_dir(id) / job_yaml_name) << "name: [not read again\n";
    runner.enqueue(id);
    runner.wait_idle();
    const JobRecord r = store.get(id);
    EXPECT_EQ(r.state, JobState::planned) << r.reason;
    EXPECT_EQ(settings_made, 1);
    EXPECT_THAT(read_file(store.plan_dir(id) / "report.json"), HasSubstr("\"bar\""));
    EXPECT_TRUE(fs::exists(store.plan_dir(id) / "print.json"));
}

TEST_F(PlanRunnerTest, FailedPlanMarksThatJobFailedWhileAnotherPlans) {
    JobStore store(options());
    store.load_all();
    PlanRunner runner(store, runner_options(2));
    const auto broken = store.submit(broken_).id;
    const auto good = store.submit(bar_).id;
    runner.enqueue(broken);
    runner.enqueue(good);
    runner.wait_idle();
    const JobRecord b = store.get(broken);
    EXPECT_EQ(b.state, JobState::failed);
    EXPECT_THAT(b.reason, HasSubstr("carries no stress field"));
    const auto disk = nlohmann::json::parse(read_file(store.job_dir(broken) / "state.json"));
    EXPECT_EQ(disk["state"], "failed");
    EXPECT_EQ(disk["reason"], b.reason);
    EXPECT_FALSE(fs::exists(store.plan_dir(broken) / "report.json"));
    EXPECT_EQ(store.get(good).state, JobState::planned);
    EXPECT_TRUE(fs::exists(store.plan_dir(good) / "report.json"));
}

TEST_F(PlanRunnerTest, AbortCancelsTheRunningPlanAndTheNextJobPlans) {
    JobStore store(options());
    store.load_all();
    PlanRunner runner(store, runner_options(1));
    std::once_flag once;
    runner.on_progress([&](std::int64_t id, const JobProgress&) {
        if (id == 1) std::call_once(once, [&] { runner.abort(1); });  // mid-plan, from the sink
    });
    runner.enqueue(store.submit(bar_).id);
    runner.enqueue(store.submit(bar_).id);
    runner.wait_idle();
    EXPECT_EQ(store.get(1).state, JobState::aborted);
    EXPECT_EQ(store.get(1).reason, "aborted by the operator");
    EXPECT_FALSE(fs::exists(store.plan_dir(1) / "report.json"));
    EXPECT_EQ(store.get(2).state, JobState::planned);
    // Aborting again is a conflict with the reason.
    try {
        runner.abort(1);
        FAIL();
    } catch (const JobConflict& e) {
        EXPECT_STREQ(e.what(), "job 1 is aborted: it has ended already");
    }
}

TEST_F(PlanRunnerTest, AbortedQueuedJobIsNeverPlanned) {
    JobStore store(options());
    store.load_all();
    std::promise<void> first_started;
    std::promise<void> release;
    std::shared_future<void> released = release.get_future().share();
    std::once_flag once;
    PlanRunner runner(store, runner_options(1));
    runner.on_progress([&](std::int64_t id, const JobProgress&) {
        if (id != 1) return;
        std::call_once(once, [&] {
            first_started.set_value();
            released.wait();  // the only worker stays on job 1 while job 2 waits
        });
    });
    runner.enqueue(store.submit(bar_).id);
    runner.enqueue(store.submit(bar_).id);
    first_started.get_future().wait();
    EXPECT_EQ(store.get(2).progress.stage, "queued");
    runner.abort(2);
    release.set_value();
    runner.wait_idle();
    EXPECT_EQ(store.get(1).state, JobState::planned);
    EXPECT_EQ(store.get(2).state, JobState::aborted);
    EXPECT_EQ(store.get(2).plan_attempts, 0);
}

TEST_F(PlanRunnerTest, ShutdownLeavesThePlanForTheNextStart) {
    {
        JobStore store(options());
        store.load_all();
        std::promise<void> started;
        std::once_flag once;
        PlanRunner runner(store, runner_options(1));
        runner.on_progress([&](std::int64_t, const JobProgress&) {
            std::call_once(once, [&] { started.set_value(); });
        });
        runner.enqueue(store.submit(bar_).id);
        started.get_future().wait();
        runner.stop();
        EXPECT_EQ(store.get(1).state, JobState::planning);
        EXPECT_EQ(store.get(1).plan_attempts, 0);  // not counted against plan_retries
    }
    JobStore store(options());
    EXPECT_EQ(store.load_all().to_plan, std::vector<std::int64_t>{1});
    PlanRunner runner(store, runner_options(1));
    runner.enqueue(1);
    runner.wait_idle();
    EXPECT_EQ(store.get(1).state, JobState::planned);
}
