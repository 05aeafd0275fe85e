// How soon planning stops when it is cancelled (a job.abort, a service stop): plans a job file as
// the service does (daemon/jobs/plan_job, the layers on a pool of 2), cancels it after a spread of
// delays and measures cancel -> plan_job returning, with the stage it was in. Its worst case is
// the longest step between two cancel checks (docs/service.md, "Stopping planning").
// Release build:  build/release/bench/plan_cancel_bench JOB.yaml [TRIALS] [WITHIN_S]
//   TRIALS (8): cancels at (i + 0.5) / TRIALS x WITHIN_S (30) seconds into the plan.

#include "daemon/jobs/plan_job.hpp"
#include "daemon/jobs/thread_pool.hpp"
#include "planner/progress.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
namespace jobs = fibrecell::daemon::jobs;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: plan_cancel_bench JOB.yaml [TRIALS] [WITHIN_S]\n");
        return 2;
    }
    spdlog::set_level(spdlog::level::warn);
    const fs::path job = argv[1];
    const int trials = argc > 2 ? std::max(1, std::atoi(argv[2])) : 8;
    const double within_s = argc > 3 ? std::atof(argv[3]) : 30;
    const fs::path out = fs::temp_directory_path() / "fibrecell-plan-cancel-bench";
    jobs::ThreadPool pool({.threads = 2});

    std::vector<double> latencies;
    std::printf("%-6s %9s %-22s %11s\n", "trial", "cancel s", "stage", "latency ms");
    for (int i = 0; i < trials; ++i) {
        fs::remove_all(out);
        fibrecell::planner::CancelToken token;
        std::mutex mu;
        std::string stage = "start";
        const fibrecell::planner::StepControl control{
            .progress = [&](std::string_view s, double) {
                std::lock_guard lock(mu);
                stage = s;
            },
            .cancel = &token};
        Clock::time_point done;
        std::string outcome = "finished";
        std::thread planner([&] {
            try {
                jobs::plan_job({.job_file = job, .out_dir = out, .executor = &pool}, control);
            } catch (const fibrecell::planner::Cancelled&) {
                outcome = "cancelled";
            } catch (const std::exception& e) {
                outcome = std::string("failed: ") + e.what();
            }
            done = Clock::now();
        });
        const double delay_s = (i + 0.5) / trials * within_s;
        const Clock::time_point start = Clock::now();
        std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                  std::chrono::duration<double>(delay_s)));
        std::string at;
        {
            std::lock_guard lock(mu);
            at = stage;
        }
        const Clock::time_point cancelled = Clock::now();
        token.cancel();
        planner.join();
        if (outcome != "cancelled") {
            std::printf("%-6d %9.1f %-22s %s before the cancel\n", i, delay_s, at.c_str(), outcome.c_str());
            continue;
        }
        const double ms = std::chrono::duration<double, std::milli>(done - cancelled).count();
        latencies.push_back(ms);
        std::printf("%-6d %9.1f %-22s %11.1f\n", i, delay_s, at.c_str(), ms);
        std::fflush(stdout);
    }
    fs::remove_all(out);
    if (latencies.empty()) return 0;
    std::sort(latencies.begin(), latencies.end());
    std::printf("cancelled %zu of %d: latency median %.1f ms, max %.1f ms\n", latencies.size(), trials,
                latencies[latencies.size() / 2], latencies.back());
    return 0;
}
