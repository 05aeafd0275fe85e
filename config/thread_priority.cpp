#include "config/thread_priority.hpp"

#include <spdlog/spdlog.h>

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

namespace fibrecell::config {

namespace {

std::atomic<int> priority_{20};
std::atomic<bool> refusal_logged_{false};

}  // namespace

void set_time_critical_priority(int priority) { priority_ = std::clamp(priority, 0, 99); }

int time_critical_priority() { return priority_; }

void name_this_thread(std::string_view name) {
    ::pthread_setname_np(::pthread_self(), std::string(name.substr(0, 15)).c_str());
}

void make_thread_time_critical(std::string_view thread) {
    name_this_thread(thread);
    const int priority = priority_;
    if (priority == 0) return;
    sched_param param{};
    param.sched_priority = priority;
    const int error = ::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &param);
    if (error == 0) {
        spdlog::debug("scheduling: {} runs at SCHED_FIFO priority {}", thread, priority);
        return;
    }
    if (refusal_logged_.exchange(true)) return;
    spdlog::warn(
        "scheduling: {} cannot run at real-time priority {} ({}): the sync, serial and Modbus "
        "threads stay at nice 0, ahead of planning only; grant it with LimitRTPRIO={} "
        "(systemd), CAP_SYS_NICE, or turn it off with print.realtime_priority: 0",
        thread, priority, std::strerror(error), priority);
}

void lower_thread_priority(int nice) {
    // A thread started by a time-critical one inherits SCHED_FIFO: back to the normal policy
    // (always permitted) before the nice value can mean anything.
    if (::sched_getscheduler(0) != SCHED_OTHER) {
        sched_param normal{};
        ::pthread_setschedparam(::pthread_self(), SCHED_OTHER, &normal);
    }
    const auto self = static_cast<id_t>(::gettid());
    errno = 0;
    const int now = ::getpriority(PRIO_PROCESS, self);
    if (errno != 0 || nice <= now) return;
    if (::setpriority(PRIO_PROCESS, self, nice) != 0)
        spdlog::warn("scheduling: cannot lower a thread's priority to nice {}: {}", nice,
                     std::strerror(errno));
}

}  // namespace fibrecell::config
