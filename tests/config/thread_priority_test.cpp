// Thread priorities (config/thread_priority.hpp), read back from the kernel (/proc): a
// time-critical thread is named and runs at SCHED_FIFO at the configured priority where that is
// permitted, stays at the normal policy where it is not or when the priority is 0, and a thread
// lowered for planning leaves an inherited real-time policy.
#include "config/thread_priority.hpp"
#include "tests/support/thread_policy.hpp"

#include <gtest/gtest.h>

#include <linux/capability.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>

using namespace fibrecell;
using fibrecell::test::realtime_permitted;
using fibrecell::test::thread_policies;
using fibrecell::test::ThreadPolicy;

namespace {

// Runs `setup` on a new thread and reads that thread's policy from /proc while it still lives.
ThreadPolicy policy_of_thread(const std::string& name, const std::function<void()>& setup) {
    std::mutex mu;
    std::condition_variable cv;
    bool ready = false, done = false;
    std::thread t([&] {
        setup();
        ::pthread_setname_np(::pthread_self(), name.c_str());
        std::unique_lock lock(mu);
        ready = true;
        cv.notify_all();
        cv.wait(lock, [&] { return done; });
    });
    ThreadPolicy p;
    {
        std::unique_lock lock(mu);
        cv.wait(lock, [&] { return ready; });
        p = thread_policies(::getpid())[name];
        done = true;
    }
    cv.notify_all();
    t.join();
    return p;
}

class ThreadPriorityTest : public ::testing::Test {
  protected:
    ~ThreadPriorityTest() override { config::set_time_critical_priority(20); }
};

}  // namespace

TEST_F(ThreadPriorityTest, ATimeCriticalThreadRunsFirstInFirstOutAtTheConfiguredPriority) {
    if (!realtime_permitted(17)) GTEST_SKIP() << "this process may not use SCHED_FIFO";
    config::set_time_critical_priority(17);
    const auto p = policy_of_thread("t.critical", [] { config::make_thread_time_critical("x"); });
    EXPECT_EQ(p.policy, SCHED_FIFO);
    EXPECT_EQ(p.rt_priority, 17);
}

TEST_F(ThreadPriorityTest, TheThreadCarriesItsNameForPsAndTop) {
    std::string name;
    std::thread([&] {
        config::make_thread_time_critical("marlin.io.and.more");
        char buf[16] = {};
        ::pthread_getname_np(::pthread_self(), buf, sizeof buf);
        name = buf;
    }).join();
    EXPECT_EQ(name, "marlin.io.and.m");  // the kernel keeps 15 characters
}

TEST_F(ThreadPriorityTest, PriorityZeroKeepsTheNormalPolicy) {
    config::set_time_critical_priority(0);
    const auto p = policy_of_thread("t.zero", [] { config::make_thread_time_critical("x"); });
    EXPECT_EQ(p.policy, SCHED_OTHER);
    EXPECT_EQ(p.rt_priority, 0);
}

TEST_F(ThreadPriorityTest, WhereRealTimeIsRefusedTheThreadRunsOnAtTheNormalPolicy) {
    // A child without CAP_SYS_NICE and with RLIMIT_RTPRIO 0, as an unprivileged service without
    // LimitRTPRIO: the policy it ends up with is its exit status.
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const rlimit none{0, 0};
        __user_cap_header_struct header{_LINUX_CAPABILITY_VERSION_3, 0};
        __user_cap_data_struct caps[2] = {};
        if (::setrlimit(RLIMIT_RTPRIO, &none) != 0 ||
            ::syscall(SYS_capget, &header, caps) != 0)
            ::_exit(100);
        caps[CAP_TO_INDEX(CAP_SYS_NICE)].effective &= ~CAP_TO_MASK(CAP_SYS_NICE);
        if (::syscall(SYS_capset, &header, caps) != 0) ::_exit(101);
        config::set_time_critical_priority(20);
        config::make_thread_time_critical("t.refused");
        ::_exit(::sched_getscheduler(0));
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), SCHED_OTHER) << "100/101: the child could not drop the right";
}

TEST_F(ThreadPriorityTest, LoweringAThreadForPlanningLeavesAnInheritedRealTimePolicy) {
    if (!realtime_permitted(20)) GTEST_SKIP() << "this process may not use SCHED_FIFO";
    config::set_time_critical_priority(20);
    const auto p = policy_of_thread("t.lowered", [] {
        config::make_thread_time_critical("x");
        config::lower_thread_priority(12);
    });
    EXPECT_EQ(p.policy, SCHED_OTHER);
    EXPECT_EQ(p.nice, std::max(12, ::getpriority(PRIO_PROCESS, 0)));
}
