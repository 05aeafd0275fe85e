// Thread priorities in fibrecelld as it runs (docs/service.md, "Thread priorities"), read from the
// kernel: during a print the sync engine, the serial link and the Modbus poll run SCHED_FIFO at
// print.realtime_priority where the process may (else the log says why not), the planning
// threads at jobs.planner_nice; print.realtime_priority 0 leaves every thread at the normal policy.
#include "service_fixture.hpp"
#include "tests/support/thread_policy.hpp"

#include <gmock/gmock.h>

using namespace fibrecell;
using namespace fibrecell::test;

namespace {

// The service's time-critical threads: the drivers' and the simulated devices' (in-process).
constexpr const char* time_critical[] = {"sync.engine", "sync.replies", "marlin.io",
                                         "robot_io.poll", "sim.board", "sim.motion"};

// Waits until every time-critical thread exists (the sync engine's only while printing) and
// returns the service's threads as they were then.
std::map<std::string, ThreadPolicy> threads_while_printing(pid_t pid) {
    std::map<std::string, ThreadPolicy> seen;
    eventually([&] {
        seen = thread_policies(pid);
        for (const char* name : time_critical)
            if (!seen.contains(name)) return false;
        return true;
    }, 60s, 1ms);
    return seen;
}

std::string names(const std::map<std::string, ThreadPolicy>& threads) {
    std::string s;
    for (const auto& [name, p] : threads)
        s += name + " (policy " + std::to_string(p.policy) + ", rt " + std::to_string(p.rt_priority) +
             ", nice " + std::to_string(p.nice) + ")\n";
    return s;
}

}  // namespace

TEST_F(ServiceTest, TheThreadsThatKeepTheCellInStepRunAheadOfEverythingElse) {
    start_service(write_config("print: {realtime_priority: 23}\n", 5));
    auto c = client();
    const std::int64_t id = submit_bar(c, true);
    const auto threads = threads_while_printing(service_->pid());
    const bool permitted = realtime_permitted(23);
    for (const char* name : time_critical) {
        ASSERT_TRUE(threads.contains(name)) << "no thread " << name << " in\n" << names(threads);
        const ThreadPolicy& p = threads.at(name);
        EXPECT_EQ(p.policy, permitted ? SCHED_FIFO : SCHED_OTHER) << name;
        EXPECT_EQ(p.rt_priority, permitted ? 23 : 0) << name;
    }
    if (!permitted) {
        EXPECT_THAT(service_->log(), ::testing::HasSubstr("cannot run at real-time priority 23"));
    }
    // The main thread (the API and the job store) keeps the normal policy.
    EXPECT_EQ(threads.at("fibrecelld").policy, SCHED_OTHER) << names(threads);
    c.call("job.abort", {{"job", id}});
}

TEST_F(ServiceTest, RealtimePriorityZeroLeavesEveryThreadAtTheNormalPolicy) {
    start_service(write_config("print: {realtime_priority: 0}\n", 5));
    auto c = client();
    const std::int64_t id = submit_bar(c, true);
    for (const auto& [name, p] : threads_while_printing(service_->pid())) {
        EXPECT_EQ(p.policy, SCHED_OTHER) << name;
        EXPECT_EQ(p.rt_priority, 0) << name;
    }
    c.call("job.abort", {{"job", id}});
}
