// A busy machine (issue 17, item 11): a running fibrecelld prints a job N times back to back
// while CPU hogs spin (processes of this bench, one per hog, at nice 0) and a planning job keeps
// the planner busy (submitted, planned, removed, again). It reports for every print its outcome,
// how often the cell paused by itself (a fault: the job went to paused without anyone asking;
// the bench resumes it and goes on), the cut position error, and at the end the robot link's
// worst cases from cell.status: the Modbus poll cycle, the gap between two service heartbeats
// (FcMain holds the robot beyond print.heartbeat_timeout_s) and between two robot heartbeats.
//
//   fibrecelld --config config/cell-demo.yaml --state-dir /tmp/bb --socket /tmp/bb/api.sock &
//   build/release/bench/busy_bench /tmp/bb/api.sock examples/tensile-bar/tensile-bar.job.yaml
//       examples/loop/loop.job.yaml 10 2   (one command line)
#include "bench_files.hpp"
#include "config/base64.hpp"
#include "daemon/api/api_client.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace fibrecell;
using namespace std::chrono_literals;
using nlohmann::json;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

namespace {

using bench::read_file;

// The job's mesh file: `mesh: NAME` in its model section, beside the job file.
std::string mesh_of(const std::string& job_yaml) {
    const auto at = job_yaml.find("mesh:");
    if (at == std::string::npos) throw std::runtime_error("the job names no mesh");
    std::string name = job_yaml.substr(at + 5, job_yaml.find_first_of("\n}#,", at) - at - 5);
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    return name;
}

json submit(api::ApiClient& c, const fs::path& job, bool start) {
    const std::string yaml = read_file(job);
    const std::string mesh = mesh_of(yaml);
    return c.call("job.submit",
                  {{"job_yaml", yaml},
                   {"files", {{mesh, config::base64_encode(read_file(job.parent_path() / mesh))}}},
                   {"start", start}},
                  60s);
}

bool ended(const std::string& s) {
    return s == "completed" || s == "completed_with_warnings" || s == "failed" || s == "aborted";
}

// CPU hogs: child processes spinning until killed.
std::vector<pid_t> start_hogs(int n) {
    std::vector<pid_t> pids;
    for (int i = 0; i < n; ++i) {
        const pid_t pid = fork();
        if (pid == 0) {
            volatile unsigned long x = 0;
            for (;;) x = x + 1;
        }
        if (pid > 0) pids.push_back(pid);
    }
    return pids;
}

// Keeps one planning job going until `stop`: submit, wait for the plan, remove, again.
void plan_forever(const std::string& socket, const fs::path& job, const std::atomic<bool>& stop,
                  std::atomic<int>& plans) {
    auto c = api::ApiClient::connect({.socket_path = socket});
    while (!stop) {
        const auto id = submit(c, job, false).value("id", std::int64_t{0});
        std::string state;
        while (!stop) {
            state = c.call("job.get", {{"job", id}}).value("state", "");
            if (state != "queued" && state != "planning") break;
            std::this_thread::sleep_for(200ms);
        }
        if (state == "planning" || state == "queued") c.call("job.abort", {{"job", id}});
        if (state == "planned") ++plans;
        try {
            c.call("job.remove", {{"job", id}});
        } catch (const std::exception&) {
            // aborted a moment ago: removed with the next prune
        }
    }
}

struct PrintFigures {
    std::string state;
    int self_pauses = 0;
    double elapsed_s = 0;
    double cut_p99_mm = 0, cut_max_mm = 0;
    long long cuts = 0;
};

PrintFigures print_once(api::ApiClient& c, const fs::path& job) {
    const auto id = submit(c, job, true).value("id", std::int64_t{0});
    PrintFigures f;
    json j;
    for (;;) {
        std::this_thread::sleep_for(50ms);
        j = c.call("job.get", {{"job", id}});
        const std::string state = j.value("state", "");
        // Back to planned with a reason: the start was refused (planned without one: on its way).
        if (ended(state) || (state == "planned" && !j.value("reason", "").empty())) break;
        if (state == "paused") {
            ++f.self_pauses;
            std::printf("    self-pause: %s\n", j.value("reason", "").c_str());
            c.call("job.resume", {{"job", id}});
        }
    }
    f.state = j.value("state", "");
    if (j.contains("result")) {
        const json& r = j["result"];
        f.elapsed_s = r.value("elapsed_s", 0.0);
        if (r.contains("cut_error_mm")) {
            f.cuts = r["cut_error_mm"].value("count", 0LL);
            f.cut_p99_mm = r["cut_error_mm"].value("p99", 0.0);
            f.cut_max_mm = r["cut_error_mm"].value("max", 0.0);
        }
    }
    return f;
}

}  // namespace

int main(int argc, char** argv) {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    if (argc < 4) {
        std::fprintf(stderr, "usage: busy_bench SOCKET PRINT_JOB.yaml PLAN_JOB.yaml [prints=10] [hogs=2]\n");
        return 2;
    }
    const std::string socket = argv[1];
    const fs::path print_job = argv[2], plan_job = argv[3];
    const int prints = argc > 4 ? std::stoi(argv[4]) : 10;
    const int hogs = argc > 5 ? std::stoi(argv[5]) : 2;
    auto c = api::ApiClient::connect({.socket_path = socket});
    std::printf("busy_bench: %d prints of %s, %d CPU hogs, %s planning meanwhile\n", prints,
                print_job.filename().c_str(), hogs, plan_job.filename().c_str());
    const std::vector<pid_t> hog_pids = start_hogs(hogs);
    std::atomic<bool> stop{false};
    std::atomic<int> plans{0};
    std::thread planner([&] {
        try {
            plan_forever(socket, plan_job, stop, plans);
        } catch (const std::exception& e) {
            std::printf("  planning load stopped: %s\n", e.what());
        }
    });
    int pauses = 0, clean = 0;
    double p99_max = 0, cut_max = 0;
    for (int i = 1; i <= prints; ++i) {
        const PrintFigures f = print_once(c, print_job);
        pauses += f.self_pauses;
        if ((f.state == "completed" || f.state == "completed_with_warnings") && f.self_pauses == 0) ++clean;
        p99_max = std::max(p99_max, f.cut_p99_mm);
        cut_max = std::max(cut_max, f.cut_max_mm);
        std::printf("  print %2d: %s in %.1f s, %d self-pauses, %lld cuts, error p99 %.3f max %.3f mm\n",
                    i, f.state.c_str(), f.elapsed_s, f.self_pauses, f.cuts, f.cut_p99_mm, f.cut_max_mm);
    }
    stop = true;
    planner.join();
    for (const pid_t p : hog_pids) {
        kill(p, SIGKILL);
        waitpid(p, nullptr, 0);
    }
    const json robot = c.call("cell.status")["robot"];
    const json worst = robot.value("worst", json::object());
    std::printf("summary: %d of %d prints completed without a self-pause (%d self-pauses), %d plans "
                "meanwhile; cut error p99 (worst print) %.3f mm, max %.3f mm\n",
                clean, prints, pauses, plans.load(), p99_max, cut_max);
    std::printf("robot link worst cases: poll cycle %.1f ms, service heartbeat gap %.1f ms, robot "
                "heartbeat gap %.1f ms\n",
                worst.value("poll_ms", 0.0), worst.value("heartbeat_gap_ms", 0.0),
                worst.value("robot_heartbeat_gap_ms", 0.0));
    return clean == prints ? 0 : 1;
}
