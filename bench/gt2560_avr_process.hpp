#pragma once
// gt2560-avr (the AVR board simulator) as the benchmarks run it: the process with its pty and
// edge log, its simulated clock against the host's, and the edges it logged.

#include "tests/support/piped_process.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace fibrecell::bench {

class Gt2560AvrProcess {
  public:
    using Clock = std::chrono::steady_clock;

    // Runs BUILD_DIR's tools/gt2560-avr on its test firmware; port() is empty when it is not
    // built or did not come up.
    Gt2560AvrProcess(const std::string& build_dir, const std::filesystem::path& dir) {
        const std::string tool = build_dir + "/tools/gt2560-avr";
        const std::string firmware = build_dir + "/tests/firmware/gt2560-test-firmware.elf";
        if (!std::filesystem::exists(tool) || !std::filesystem::exists(firmware)) return;
        port_ = (dir / "ttyAvr").string();
        edge_log_ = dir / "edges.log";
        process_.emplace(tool, std::vector<std::string>{firmware, "--link", port_, "--edge-log",
                                                        edge_log_.string()});
        if (!process_->read_line_starting("port ", std::chrono::seconds(20))) port_.clear();
    }
    ~Gt2560AvrProcess() {
        if (!process_) return;
        process_->write_line("quit");
        process_->wait(std::chrono::seconds(10));
    }

    const std::string& port() const { return port_; }
    const std::filesystem::path& edge_log() const { return edge_log_; }

    // One `status` answer (it also flushes the edge log).
    std::string status() {
        process_->write_line("status");
        return process_->read_line_starting("status ", std::chrono::seconds(10)).value_or("");
    }

    // The simulator's clock against the host's: a status answer's sim_time_s taken at the middle
    // of its round trip (off by at most half of it).
    struct ClockMap {
        double offset_s = 0;  // host seconds since t_ref - simulated seconds
        double half_rtt_ms = 0;
    };
    ClockMap map_clock(Clock::time_point t_ref) {
        const auto q0 = Clock::now();
        const std::string st = status();
        const auto q1 = Clock::now();
        const double mid = std::chrono::duration<double>(q0 - t_ref).count() +
                           std::chrono::duration<double>(q1 - q0).count() / 2;
        const auto at = st.find("\"sim_time_s\":");
        const double sim = at == std::string::npos ? -1 : std::strtod(st.c_str() + at + 13, nullptr);
        return {mid - sim, std::chrono::duration<double, std::milli>(q1 - q0).count() / 2};
    }

    struct Edge {
        double t_s;  // simulated
        std::string pin;
        int level;
    };
    // The edges logged since the last call (`status()` first, so that they are flushed).
    std::vector<Edge> new_edges() {
        if (!edges_.is_open()) edges_.open(edge_log_);
        edges_.clear();
        std::vector<Edge> out;
        std::string line;
        while (std::getline(edges_, line)) {
            double t = 0;
            char pin[32] = {};
            int level = 0;
            if (std::sscanf(line.c_str(), "%lf %31s %d", &t, pin, &level) == 3)
                out.push_back({t, pin, level});
        }
        return out;
    }

  private:
    std::optional<test::PipedProcess> process_;
    std::string port_;
    std::filesystem::path edge_log_;
    std::ifstream edges_;
};

}  // namespace fibrecell::bench
