#pragma once
// The scheduling of a process's threads as the kernel reports it (/proc/<pid>/task/*/stat), and
// whether this process may ask for real time: what the tests of config/thread_priority.hpp read,
// independently of the code that sets it.

#include <pthread.h>
#include <sched.h>
#include <sys/types.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>

namespace fibrecell::test {

struct ThreadPolicy {
    int policy = -1;       // SCHED_OTHER 0, SCHED_FIFO 1, ...
    int rt_priority = -1;  // 1..99 under a real-time policy, else 0
    int nice = 0;
};

// Every thread of `pid` by name (the last one of a name wins).
inline std::map<std::string, ThreadPolicy> thread_policies(pid_t pid) {
    std::map<std::string, ThreadPolicy> out;
    std::error_code ec;
    for (const auto& task :
         std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task", ec)) {
        std::ifstream in(task.path() / "stat");
        std::string stat((std::istreambuf_iterator<char>(in)), {});
        const auto open = stat.find('('), close = stat.rfind(')');
        if (open == std::string::npos || close == std::string::npos) continue;
        const std::string name = stat.substr(open + 1, close - open - 1);
        std::istringstream fields(stat.substr(close + 2));
        std::string field;
        ThreadPolicy p;
        // Fields 3.. of proc(5): nice is 19, rt_priority 40, policy 41.
        for (int n = 3; fields >> field; ++n) {
            if (n == 19) p.nice = std::stoi(field);
            if (n == 40) p.rt_priority = std::stoi(field);
            if (n == 41) p.policy = std::stoi(field);
        }
        out[name] = p;
    }
    return out;
}

// Whether a thread of this process may switch itself to SCHED_FIFO at `priority`.
inline bool realtime_permitted(int priority) {
    bool ok = false;
    std::thread([&] {
        sched_param p{};
        p.sched_priority = priority;
        ok = ::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &p) == 0;
    }).join();
    return ok;
}

}  // namespace fibrecell::test
