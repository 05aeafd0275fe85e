#include "tools/fibrecell/service_commands.hpp"

#include "config/base64.hpp"
#include "config/printable.hpp"
#include "daemon/api/api_client.hpp"
#include "planner/job/job_spec.hpp"
#include "tools/fibrecell/job_view.hpp"
#include "tools/fibrecell/service_connection.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

namespace fibrecell::tools {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + p.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The job YAML with every file it names (relative to its folder), for job.submit.
json submit_params(const fs::path& job_file, bool start) {
    const planner::JobSpec spec = planner::load_job_file(job_file.string());  // checked here first
    const fs::path dir = fs::weakly_canonical(fs::absolute(job_file)).parent_path();
    json files = json::object();
    for (const std::string& path : {spec.model.mesh_path, spec.model.stress_path}) {
        if (path.empty()) continue;
        const fs::path rel = fs::weakly_canonical(path).lexically_relative(dir);
        if (rel.empty() || *rel.begin() == "..")
            throw std::runtime_error(path + ": a job's files must be in its folder or below it");
        files[rel.generic_string()] = config::base64_encode(read_text(path));
    }
    return {{"job_yaml", read_text(job_file)}, {"files", files}, {"start", start}};
}

std::int64_t current_job(api::ApiClient& client) {
    const json cell = client.call("cell.status");
    if (cell.contains("job") && cell["job"].is_number_integer()) return cell["job"].get<std::int64_t>();
    const json jobs = client.call("job.list");
    if (jobs.empty()) throw std::runtime_error("the service has no jobs");
    return jobs.back().value("id", std::int64_t{0});
}

void print_folders(const json& job) {
    if (!job.contains("dir")) return;
    const fs::path dir = job["dir"].get<std::string>();
    std::cout << "  job folder  " << dir.string() << "\n";
    if (fs::exists(dir / "plan/preview/index.html"))
        std::cout << "  preview     " << (dir / "plan/preview/index.html").string() << "\n";
    if (fs::exists(dir / "plan/report.json"))
        std::cout << "  report      " << (dir / "plan/report.json").string() << "\n";
    if (fs::exists(dir / "result.json"))
        std::cout << "  result      " << (dir / "result.json").string() << "\n";
}

// Follows a job until it ends (or its start is refused; with `until_paused`, or it pauses): a
// live line (redrawn in place on a terminal, else a line every few seconds), a line for every
// state change; returns the exit code (0 completed).
int watch(const Connection& c, api::ApiClient& client, std::int64_t id, bool until_paused) {
    const bool tty = ::isatty(STDOUT_FILENO) && !c.json_output;
    client.call("subscribe", {{"topics", json::array({std::to_string(id), "cell"})}});
    json job = client.call("job.get", {{"job", id}});
    json cell = client.call("cell.status");
    std::string state = job.value("state", "");
    if (!c.json_output)
        std::cout << "watching job " << id << " (" << config::printable(job.value("name", ""))
                  << "): " << state << "\n";
    std::string last_line, last_progress;
    auto last_print = std::chrono::steady_clock::now() - 1h;
    auto last_refresh = std::chrono::steady_clock::now();
    // A start that was refused sends the job back to planned (or interrupted) with the reason:
    // after `starting`, that is where this watch ends too.
    bool started = state == "starting";
    // A job submitted with `start` whose start the cell refused once it was planned (a bed not
    // yet cleared): its view says why, and nothing more will happen by itself.
    const auto not_started = [&] { return state == "planned" && job.contains("start_refused"); };
    const auto ended = [&] {
        return is_final_state(state) || (started && (state == "planned" || state == "interrupted")) ||
               (until_paused && state == "paused") || not_started();
    };
    while (!ended()) {
        const auto n = client.next_notification(500ms);
        if (n) {
            if (c.json_output) std::cout << json{{"method", n->method}, {"params", n->params}}.dump() << std::endl;
            if (n->method == "notify.job_state" && n->params.value("id", std::int64_t{0}) == id) {
                job = n->params;
            } else if (n->method == "notify.job_progress" && n->params.value("job", std::int64_t{0}) == id) {
                for (const char* k : {"planning", "print"})
                    if (n->params.contains(k)) job[k] = n->params[k];
                if (n->params.value("state", "") == "printing") job.erase("planning");
            } else if (n->method == "notify.cell_status") {
                cell = n->params;
            }
        }
        if (std::chrono::steady_clock::now() - last_refresh > 5s) {  // a missed notification
            job = client.call("job.get", {{"job", id}});
            last_refresh = std::chrono::steady_clock::now();
        }
        const std::string now_state = job.value("state", "");
        if (now_state != state) {
            state = now_state;
            started = started || state == "starting";
            if (!c.json_output) {
                if (tty) std::cout << "\r\x1b[K";
                std::cout << "job " << id << ": " << state
                          << (job.contains("reason")
                                  ? " (" + config::printable(job.value("reason", "")) + ")"
                                  : "")
                          << "\n";
                if (state == "paused" && job.contains("reason"))
                    std::cout << "  the cell is safe; `fibrecell resume " << id << "` goes on, `fibrecell abort "
                              << id << "` ends it\n";
                std::cout << std::flush;
                last_line.clear();
            }
            continue;
        }
        if (c.json_output) continue;
        const std::string line = live_line(job, cell);
        const auto now = std::chrono::steady_clock::now();
        if (line.empty() || line == last_line) continue;
        if (tty) {
            std::cout << "\r\x1b[K" << line << std::flush;
            last_line = line;
        } else {
            // Not a terminal (a log, CI): a line when the progress moves, at most every 2 s,
            // and every 30 s while it does not.
            const std::string progress = live_line(job, json::object());
            const bool moved = progress.substr(0, progress.rfind("  ")) != last_progress;
            if ((moved && now - last_print > 2s) || now - last_print > 30s) {
                std::cout << line << std::endl;  // live: a pipe or file is block-buffered
                last_line = line;
                last_progress = progress.substr(0, progress.rfind("  "));
                last_print = now;
            }
        }
    }
    job = client.call("job.get", {{"job", id}});
    if (c.json_output) {
        std::cout << job.dump() << "\n";
    } else {
        if (tty) std::cout << "\r\x1b[K";
        if (job.value("state", "") == "planned" && job.contains("start_refused"))
            std::cout << "job " << id << " planned; not started: "
                      << config::printable(job.value("start_refused", "")) << "\n";
        else
            std::cout << outcome_line(job) << "\n";
        print_folders(job);
    }
    return job.value("state", "") == "completed" ? 0 : 1;
}

// For scripts that cannot resume a job (CI, tools/try-firmware.sh): a pause ends the watch too.
void add_until_paused(CLI::App& cmd, bool& flag) {
    cmd.add_flag("--until-paused", flag,
                 "also end when the job pauses (exit 1), instead of following it until resumed");
}

// One verb that names a job (or defaults to the job on the cell) and prints the new state.
void add_job_action(CLI::App& app, int& exit_code, const std::string& verb, const std::string& method,
                    const std::string& help, bool job_required) {
    auto* cmd = app.add_subcommand(verb, help);
    auto c = std::make_shared<Connection>();
    auto id = std::make_shared<std::int64_t>(0);
    auto* opt = cmd->add_option("job", *id, "job id");
    if (job_required) opt->required();
    auto journal_lost = std::make_shared<bool>(false);
    if (method == "job.resume")
        cmd->add_flag("--journal-lost", *journal_lost,
                      "the job's journal is lost: go on after the last event its state.json saw "
                      "(look at the part first; later events may print again)");
    add_connection_options(*cmd, *c);
    cmd->callback([&exit_code, c, id, journal_lost, method, verb] {
        guarded(exit_code, [&] {
            api::ApiClient client = c->connect();
            json params = json::object();
            if (*id != 0) params["job"] = *id;
            if (*journal_lost) params["journal_lost"] = true;
            const json answer = client.call(method, params);
            if (method == "job.remove")
                print(*c, answer, "job " + std::to_string(answer.value("removed", 0)) + " removed\n");
            else
                print(*c, answer, "job " + std::to_string(answer.value("id", 0)) + ": " +
                                      answer.value("state", "") + "\n");
            return 0;
        });
    });
}

}  // namespace

void add_service_commands(CLI::App& app, int& exit_code) {
    {
        auto* cmd = app.add_subcommand("submit", "submit a job to the service (planned there)");
        auto c = std::make_shared<Connection>();
        auto file = std::make_shared<std::string>();
        auto start = std::make_shared<bool>(false);
        auto follow = std::make_shared<bool>(false);
        auto until_paused = std::make_shared<bool>(false);
        cmd->add_option("job", *file, "job YAML")->required()->check(CLI::ExistingFile);
        cmd->add_flag("--start", *start, "print it as soon as it is planned");
        cmd->add_flag("--watch", *follow, "follow it until it ends");
        add_until_paused(*cmd, *until_paused);
        add_connection_options(*cmd, *c);
        cmd->callback([&exit_code, c, file, start, follow, until_paused] {
            guarded(exit_code, [&] {
                const json params = submit_params(*file, *start);
                api::ApiClient client = c->connect();
                const json job = client.call("job.submit", params, 60s);
                const auto id = job.value("id", std::int64_t{0});
                if (!*follow || c->json_output) print(*c, job, "");
                if (!c->json_output)
                    std::cout << "job " << id << " (" << config::printable(job.value("name", ""))
                              << ") submitted: "
                              << job.value("state", "") << (*start ? ", prints when planned" : "") << "\n";
                return *follow ? watch(*c, client, id, *until_paused) : 0;
            });
        });
    }
    {
        auto* cmd = app.add_subcommand("jobs", "list the service's jobs");
        auto c = std::make_shared<Connection>();
        add_connection_options(*cmd, *c);
        cmd->callback([&exit_code, c] {
            guarded(exit_code, [&] {
                api::ApiClient client = c->connect();
                const json jobs = client.call("job.list");
                print(*c, jobs, jobs_table(jobs));
                return 0;
            });
        });
    }
    {
        auto* cmd = app.add_subcommand("status", "the cell, or one job");
        auto c = std::make_shared<Connection>();
        auto id = std::make_shared<std::int64_t>(0);
        cmd->add_option("job", *id, "job id");
        add_connection_options(*cmd, *c);
        cmd->callback([&exit_code, c, id] {
            guarded(exit_code, [&] {
                api::ApiClient client = c->connect();
                if (*id != 0) {
                    const json job = client.call("job.get", {{"job", *id}});
                    print(*c, job, job_details(job));
                } else {
                    const json cell = client.call("cell.status");
                    print(*c, cell, cell_details(cell));
                }
                return 0;
            });
        });
    }
    add_job_action(app, exit_code, "start", "job.start", "print a planned job", true);
    add_job_action(app, exit_code, "pause", "job.pause", "pause the print (default: the job on the cell)", false);
    add_job_action(app, exit_code, "resume", "job.resume", "resume a paused or interrupted job", false);
    add_job_action(app, exit_code, "abort", "job.abort", "abort a job (a running print stops safely)", false);
    add_job_action(app, exit_code, "remove", "job.remove", "delete an ended job's folder", true);
    add_job_action(app, exit_code, "replan", "job.replan",
                   "plan a planned (or plan-failed) job again, e.g. after the cell changed", true);
    {
        auto* cmd = app.add_subcommand("watch", "follow a job's progress until it ends");
        auto c = std::make_shared<Connection>();
        auto id = std::make_shared<std::int64_t>(0);
        auto until_paused = std::make_shared<bool>(false);
        cmd->add_option("job", *id, "job id (default: the job on the cell, else the latest)");
        add_until_paused(*cmd, *until_paused);
        add_connection_options(*cmd, *c);
        cmd->callback([&exit_code, c, id, until_paused] {
            guarded(exit_code, [&] {
                api::ApiClient client = c->connect();
                return watch(*c, client, *id != 0 ? *id : current_job(client), *until_paused);
            });
        });
    }
    {
        auto* cmd = app.add_subcommand("estop", "M112 and the robot's abort request (NOT a safety function)");
        auto c = std::make_shared<Connection>();
        add_connection_options(*cmd, *c);
        cmd->callback([&exit_code, c] {
            guarded(exit_code, [&] {
                api::ApiClient client = c->connect();
                const json answer = client.call("cell.estop");
                print(*c, answer, "estop sent: " + answer.value("note", std::string()) + "\n");
                return 0;
            });
        });
    }
}

}  // namespace fibrecell::tools
