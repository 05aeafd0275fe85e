// The service under load from a second process (issue 7): prints a job on a running fibrecelld
// twice, first alone, then while this process calls cell.status about 1,000 times per second,
// and reports the calls/s reached, the call latency, the sync engine's event -> board command
// latency of each print (median, p99 from the job's result.json) and the service's memory (VmRSS)
// idle and during the prints.
//
//   fibrecelld --config config/cell-sim.yaml --state-dir /tmp/fb --socket /tmp/fb/api.sock &
//   build/release/bench/service_bench /tmp/fb/api.sock examples/tensile-bar/tensile-bar.job.yaml
#include "bench_files.hpp"
#include "config/base64.hpp"
#include "daemon/api/api_client.hpp"

#include <algorithm>
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

long rss_kib(long pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return -1;
}

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

// Submits the job (files beside it: the mesh named in `model.mesh`), waits until it is printed;
// with `load`, calls cell.status at ~1 kHz meanwhile. Returns the job as it ended.
json print_once(api::ApiClient& c, const std::string& socket, const fs::path& job, const std::string& mesh,
                bool load, long pid, long& peak_rss) {
    const json submitted = c.call("job.submit",
                                  {{"job_yaml", read_file(job)},
                                   {"files", {{mesh, config::base64_encode(read_file(job.parent_path() / mesh))}}},
                                   {"start", true}},
                                  60s);
    const auto id = submitted.value("id", std::int64_t{0});
    std::vector<double> call_ms;
    auto poller = api::ApiClient::connect({.socket_path = socket});
    const auto start = Clock::now();
    std::size_t calls = 0;
    json j;
    for (;;) {
        if (load) {
            for (int i = 0; i < 100; ++i) {  // 100 calls, then pace to 1 kHz
                const auto t0 = Clock::now();
                poller.call("cell.status");
                call_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
                ++calls;
                std::this_thread::sleep_until(start + std::chrono::microseconds(1000 * calls));
            }
        } else {
            std::this_thread::sleep_for(100ms);
        }
        j = c.call("job.get", {{"job", id}});
        peak_rss = std::max(peak_rss, rss_kib(pid));
        const std::string state = j.value("state", "");
        if (state == "completed" || state == "completed_with_warnings" ||
            state == "failed" || state == "aborted" || state == "paused" ||
            state == "planned")  // planned again: the start was refused
            break;
    }
    const double secs = std::chrono::duration<double>(Clock::now() - start).count();
    if (load)
        std::printf("  cell.status: %zu calls in %.1f s = %.0f calls/s, latency median %.3f ms p99 %.3f ms\n",
                    calls, secs, static_cast<double>(calls) / secs, percentile(call_ms, 0.5),
                    percentile(call_ms, 0.99));
    return j;
}

void report(const char* what, const json& job) {
    std::printf("%s: job %lld %s", what, static_cast<long long>(job.value("id", std::int64_t{0})),
                job.value("state", "").c_str());
    if (!job.contains("result")) {
        std::printf("\n");
        return;
    }
    const json& r = job["result"];
    std::printf(", %.1f s\n", r.value("elapsed_s", 0.0));
    if (!r.contains("latency_ms")) return;
    for (const auto& [kind, s] : r.at("latency_ms").items())
        std::printf("    %-12s event -> board command n=%-5lld median %.3f ms  p99 %.3f ms\n", kind.c_str(),
                    s.value("count", 0LL), s.value("median", 0.0), s.value("p99", 0.0));
}

}  // namespace

int main(int argc, char** argv) {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);  // a line at a time, also into a pipe
    if (argc < 3) {
        std::fprintf(stderr, "usage: service_bench SOCKET JOB.yaml [MESH (default: <job stem>.msh)]\n");
        return 2;
    }
    const std::string socket = argv[1];
    const fs::path job = argv[2];
    std::string mesh = argc > 3 ? argv[3] : job.stem().stem().string() + ".msh";
    auto c = api::ApiClient::connect({.socket_path = socket});
    const long pid = c.call("server.info").value("pid", 0L);
    std::printf("service_bench: fibrecelld pid %ld, idle VmRSS %ld KiB\n", pid, rss_kib(pid));
    long peak_alone = 0, peak_loaded = 0;
    const json alone = print_once(c, socket, job, mesh, false, pid, peak_alone);
    report("print alone", alone);
    std::printf("  peak VmRSS %ld KiB\n", peak_alone);
    const json loaded = print_once(c, socket, job, mesh, true, pid, peak_loaded);
    report("print with 1,000 cell.status/s", loaded);
    std::printf("  peak VmRSS %ld KiB\n", peak_loaded);
    return 0;
}
