#pragma once
// fibrecelld as its users run it, for the service tests: the built binary started as a child on a
// private state directory and socket (the simulated cell in-process at a high time scale, TCP on
// an ephemeral loopback port with a token), real API clients, and two small jobs: a 40 x 10 x 1.6 mm
// bar pulled along x (plans in a second or two, prints in seconds), and the same mesh without
// stress, which cannot be planned.
#include "config/base64.hpp"
#include "daemon/api/api_client.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "child_process.hpp"
#include "tests/support/plan_inputs.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>


#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <optional>
#include <iomanip>
#include <ctime>
#include <string>

namespace fibrecell::test {

using namespace std::chrono_literals;
using nlohmann::json;
namespace fs = std::filesystem;

// The planned events of a job: kind and length_mm by sequence (program.json's event table).
struct PlannedEvent {
    std::string kind;
    double length_mm = 0;
};

inline std::map<std::int64_t, PlannedEvent> planned_events(const fs::path& program_json) {
    const json p = json::parse(read_file(program_json));
    const auto& cols = p.at("event_columns");
    const auto col = [&](const std::string& name) {
        return static_cast<std::size_t>(std::find(cols.begin(), cols.end(), name) - cols.begin());
    };
    std::map<std::int64_t, PlannedEvent> out;
    for (const auto& row : p.at("events"))
        out[row.at(col("sequence")).get<std::int64_t>()] = {
            row.at(col("kind")).get<std::string>(), row.at(col("length_mm")).get<double>()};
    return out;
}

// When the service logged the first line containing `needle` (its log's local time stamps,
// "2026-12-06T06:29:16.881 error ...").
inline std::optional<std::chrono::system_clock::time_point> logged_at(const std::string& log,
                                                                      const std::string& needle) {
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);) {
        if (line.find(needle) == std::string::npos || line.size() < 23) continue;
        std::tm tm{};
        std::istringstream stamp(line.substr(0, 19));
        stamp >> std::get_time(&tm, "%Y-%m-%dT%H:%M:%S");
        if (stamp.fail()) continue;
        tm.tm_isdst = -1;
        return std::chrono::system_clock::from_time_t(std::mktime(&tm)) +
               std::chrono::milliseconds(std::stoi(line.substr(20, 3)));
    }
    return std::nullopt;
}

class ServiceTest : public ::testing::Test {
  protected:
    void SetUp() override {
        fs::create_directories(dir_ / "jobs");
        // A bar pulled along x, 40 mm long: each CCF layer lays three paths of 80 mm or more
        // (lengths of the bar joined), well past the cutter's 42 mm; 60 mm cost the service
        // tests a sixth more time and tested nothing more.
        const auto mesh = planner::structured_tet_mesh({.size = {40, 10, 1.6}, .cells = {20, 5, 2}});
        std::vector<planner::StressTensor> stress(mesh.tet_count(), planner::StressTensor::Zero());
        for (auto& s : stress) s(0, 0) = 30.0;
        fibrecell::test::write_vtk_file(dir_ / "jobs/bar.vtk", mesh, {.stress = &stress});
        fibrecell::test::write_vtk_file(dir_ / "jobs/bare.vtk", mesh, {});
        // PLA at 24 mm/s and fibre at 10 (the defaults 12 and 5 are for the fibre cell's first
        // layers; 10 mm/s is still a speed fibre heads lay at): half the robot time of each
        // print of the service tests.
        std::ofstream(dir_ / "jobs/bar.job.yaml")
            << "name: bar\nmodel:\n  mesh: bar.vtk\nplacement:\n  position_mm: [150, 150]\n"
               "process:\n  pla: {speed_mm_s: 24}\n  ccf: {speed_mm_s: 10}\n";
        std::ofstream(dir_ / "jobs/broken.job.yaml")
            << "name: broken\nmodel:\n  mesh: bare.vtk\nplacement:\n  position_mm: [150, 150]\n";
    }
    void TearDown() override {
        service_.reset();
        if (HasFailure()) {
            dir_.keep();  // the service's logs and state, for the failure
            std::cerr << "kept " << dir_.string() << "\n";
        }
    }

    fs::path socket() const { return dir_ / "api.sock"; }
    fs::path state_dir() const { return dir_ / "state"; }

    // The cell YAML of the tests; `extra` is appended (more sections or keys).
    // `simulation_extra`: more keys of the simulation section (", key: value").
    fs::path write_config(const std::string& extra = "", double time_scale = 50,
                          const std::string& simulation_extra = "") const {
        const fs::path p = dir_ / "cell.yaml";
        std::ofstream(p) << "name: test-cell\n"
                         << "log_level: info\n"
                         << "state_dir: " << state_dir().string() << "\n"
                         << "simulated: true\n"
                         << "simulation: {time_scale: " << time_scale
                         << ", hotend_tau_s: 2, residency_s: 0.5" << simulation_extra << "}\n"
                         << "robot_io: {stable_reads: 1}\n"
                         << "api:\n  socket: " << socket().string() << "\n"
                         << "  max_request_bytes: 4194304\n"
                         << "  tcp: {enabled: true, port: 0, token: test-token-0123456789}\n"
                         << "jobs: {planner_threads: 1}\n"
                         // Fibre threaded at 20 mm/s (the default 5 is a cautious first
                         // threading): each fibre start holds the robot a quarter as long.
                         << "extruder: {ccf: {thread_speed_mm_s: 20}}\n"
                         << extra;
        return p;
    }

    // The cell YAML `text` (write_config's) with the extruder board on `port`.
    static std::string with_board_port(std::string text, const fs::path& port) {
        const std::string from = "extruder: {";
        text.replace(text.find(from), from.size(), from + "link: {port: " + port.string() + "}, ");
        return text;
    }

    void start_service(const fs::path& config) {
        service_ = std::make_unique<ChildProcess>(fibrecell::test::binary_path("daemon/fibrecelld"),
                                                  std::vector<std::string>{"--config", config.string()},
                                                  dir_ / ("fibrecelld-" + std::to_string(++starts_) + ".log"));
        ASSERT_TRUE(service_->wait_for_log("fibrecelld: listening on", 30s)) << service_->log();
    }

    api::ApiClient client() const { return api::ApiClient::connect({.socket_path = socket().string()}); }

    // job.submit as the CLI sends it: the YAML text and its mesh inline.
    static json submit_params(const fs::path& job_yaml, const std::string& mesh, bool start) {
        return {{"job_yaml", read_file(job_yaml)},
                {"files", {{mesh, config::base64_encode(read_file(job_yaml.parent_path() / mesh))}}},
                {"start", start}};
    }
    std::int64_t submit_bar(api::ApiClient& c, bool start) {
        return c.call("job.submit", submit_params(dir_ / "jobs/bar.job.yaml", "bar.vtk", start), 30s)
            .value("id", std::int64_t{0});
    }
    std::int64_t submit_broken(api::ApiClient& c) {
        return c.call("job.submit", submit_params(dir_ / "jobs/broken.job.yaml", "bare.vtk", false), 30s)
            .value("id", std::int64_t{0});
    }

    // Polls job.get until the job is in `state`; the last answer (check its state).
    json wait_for_state(api::ApiClient& c, std::int64_t id, const std::string& state,
                        std::chrono::milliseconds timeout = 60s) {
        // Also done when the job ended otherwise: the test sees the state it got at once.
        const auto ended = [](const std::string& s) {
            return s == "completed" || s == "completed_with_warnings" || s == "aborted" ||
                   s == "failed";
        };
        json job;
        eventually([&] {
            job = c.call("job.get", {{"job", id}});
            const std::string now = job.value("state", "");
            return now == state || ended(now);
        }, timeout, 20ms);
        return job;
    }

    // The print ran to its end. A test of the service's flow (not of the print's quality, which
    // the sync and position tests measure) takes completed_with_warnings too, and shows why.
    static bool printed(const json& job) {
        const std::string state = job.value("state", "");
        if (state == "completed_with_warnings")
            std::cout << "note: job " << job.value("id", 0) << " " << job.value("reason", "") << "\n";
        return state == "completed" || state == "completed_with_warnings";
    }

    TempDir dir_{"service"};
    int starts_ = 0;  // each start of the service logs to a file of its own
    std::unique_ptr<ChildProcess> service_;
};

}  // namespace fibrecell::test
