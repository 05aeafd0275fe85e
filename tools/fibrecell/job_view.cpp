#include "tools/fibrecell/job_view.hpp"

#include "config/printable.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <vector>

namespace fibrecell::tools {
namespace {

using nlohmann::json;

std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

double number(const json& j, const char* key, double fallback = 0) {
    const auto it = j.find(key);
    return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

// A string of the service's answer, safe for the terminal (names and reasons come from users).
std::string text(const json& j, const char* key, const std::string& fallback = "") {
    const auto it = j.find(key);
    return it != j.end() && it->is_string() ? config::printable(it->get<std::string>()) : fallback;
}

bool has(const json& j, const char* key) {
    return j.is_object() && j.contains(key) && !j[key].is_null();
}

std::string name_of(const json& job) {
    const std::string name = text(job, "name");
    return "job " + std::to_string(job.value("id", 0)) + (name.empty() ? "" : " (" + name + ")");
}

// "PLA 199/200 °C  CCF 250/250 °C" from cell.status's board part.
std::string temperatures(const json& cell) {
    if (!has(cell, "board")) return "";
    const json& b = cell["board"];
    std::string out;
    for (const char* head : {"pla", "ccf"}) {
        const std::string key = std::string(head) + "_c";
        if (!has(b, key.c_str())) continue;
        if (!out.empty()) out += "  ";
        std::string label = head;
        std::transform(label.begin(), label.end(), label.begin(), ::toupper);
        out += label + " " + fixed(number(b, key.c_str()), 0);
        const std::string target = std::string(head) + "_target_c";
        if (has(b, target.c_str())) out += "/" + fixed(number(b, target.c_str()), 0);
        out += " C";
    }
    return out;
}

std::string percentile_pair(const json& j, const std::string& unit, int decimals) {
    return "median " + fixed(number(j, "median"), decimals) + " " + unit + ", p99 " +
           fixed(number(j, "p99"), decimals) + " " + unit;
}

}  // namespace

std::string progress_bar(double fraction, int width) {
    if (!std::isfinite(fraction)) fraction = 0;
    fraction = std::clamp(fraction, 0.0, 1.0);
    const int full = static_cast<int>(std::lround(fraction * width));
    return "[" + std::string(static_cast<std::size_t>(full), '#') +
           std::string(static_cast<std::size_t>(width - full), '-') + "]";
}

std::string duration_text(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "?";
    const auto s = static_cast<long>(std::lround(seconds));
    char buf[32];
    if (s >= 3600)
        std::snprintf(buf, sizeof buf, "%ldh%02ldm%02lds", s / 3600, s / 60 % 60, s % 60);
    else if (s >= 60)
        std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
    else
        std::snprintf(buf, sizeof buf, "%lds", s);
    return buf;
}

bool is_final_state(const std::string& state) {
    return state == "completed" || state == "completed_with_warnings" || state == "aborted" ||
           state == "failed";
}

std::string jobs_table(const json& jobs) {
    if (!jobs.is_array() || jobs.empty()) return "no jobs\n";
    std::ostringstream out;
    char line[160];
    std::snprintf(line, sizeof line, "%4s  %-20s %-12s %s\n", "ID", "NAME", "STATE", "PROGRESS");
    out << line;
    for (const json& job : jobs) {
        std::string progress;
        if (has(job, "planning"))
            progress = text(job["planning"], "stage") + " " +
                       fixed(100 * number(job["planning"], "fraction"), 0) + "%";
        else if (has(job, "print"))
            progress = "layer " + std::to_string(static_cast<int>(number(job["print"], "layer"))) +
                       "/" + std::to_string(static_cast<int>(number(job["print"], "layers"))) +
                       " " + fixed(100 * number(job["print"], "fraction"), 0) + "%";
        if (has(job, "reason")) progress += (progress.empty() ? "" : "  ") + text(job, "reason");
        std::snprintf(line, sizeof line, "%4d  %-20.20s %-12s %s\n", job.value("id", 0),
                      text(job, "name").c_str(), text(job, "state").c_str(), progress.c_str());
        out << line;
    }
    return out.str();
}

std::string job_details(const json& job) {
    std::ostringstream out;
    out << name_of(job) << ": " << text(job, "state") << "\n";
    if (has(job, "reason")) out << "  reason:   " << text(job, "reason") << "\n";
    if (has(job, "planning"))
        out << "  planning: " << text(job["planning"], "stage") << " "
            << progress_bar(number(job["planning"], "fraction")) << "\n";
    if (has(job, "plan")) {
        const json& p = job["plan"];
        out << "  plan:     " << static_cast<int>(number(p, "layers")) << " layers, fibre "
            << fixed(number(p, "fibre_length_m"), 2) << " m, PLA "
            << fixed(number(p, "pla_length_m"), 2) << " m, "
            << static_cast<int>(number(p, "events")) << " events, "
            << static_cast<int>(number(p, "modules")) << " RAPID modules, robot time "
            << duration_text(number(p, "duration_s")) << "\n";
        if (has(p, "stiffness_n_per_mm"))
            out << "  predicted: " << fixed(number(p, "stiffness_n_per_mm"), 0)
                << " N/mm along the load, " << fixed(number(p, "stiffness_gain"), 2)
                << "x the part without fibre\n";
    }
    if (has(job, "print")) {
        const json& p = job["print"];
        out << "  print:    layer " << static_cast<int>(number(p, "layer")) << "/"
            << static_cast<int>(number(p, "layers")) << " " << progress_bar(number(p, "fraction"))
            << " event " << static_cast<long>(number(p, "event")) << "/"
            << static_cast<long>(number(p, "events")) << ", elapsed "
            << duration_text(number(p, "elapsed_s"));
        if (has(p, "eta_s")) out << ", ETA " << duration_text(number(p, "eta_s"));
        out << "\n";
    }
    if (has(job, "dir")) out << "  folder:   " << text(job, "dir") << "\n";
    return out.str();
}

std::string cell_details(const json& cell) {
    std::ostringstream out;
    out << "cell " << text(cell, "name") << (cell.value("simulated", false) ? " (simulated)" : "")
        << "\n";
    if (has(cell, "board"))
        out << "  board:  " << text(cell["board"], "state") << "  " << temperatures(cell) << "\n";
    if (has(cell, "heaters")) {  // why they are on, and when they go off (docs/service.md)
        const json& h = cell["heaters"];
        out << "  heaters: " << (h.value("on", false) ? "on, " + text(h, "why") : std::string("off"));
        if (has(h, "off_in_s")) out << "; off in " << fixed(number(h, "off_in_s"), 0) << " s";
        if (!h.value("on", false) && has(h, "last_off")) out << " (" << text(h, "last_off") << ")";
        out << "\n";
    }
    if (has(cell, "robot")) {
        const json& r = cell["robot"];
        out << "  robot:  I/O " << text(r, "io")
            << (r.value("running", false) ? ", running" : ", not running");
        if (has(r, "event")) out << ", event " << static_cast<long>(number(r, "event"));
        out << "\n";
    }
    if (has(cell, "job")) out << "  job:    " << cell["job"].get<int>() << "\n";
    if (has(cell, "bed")) {
        out << "  bed:    " << bed_text(cell["bed"]);
        if (has(cell, "queue"))
            out << "; " << static_cast<long>(number(cell["queue"], "jobs")) << " queued"
                << (cell["queue"].value("paused", false) ? " (paused)" : "");
        out << "\n";
    }
    if (has(cell, "sync")) {
        const json& s = cell["sync"];
        if (has(s, "latency_ms"))
            out << "  sync:   event -> board " << percentile_pair(s["latency_ms"], "ms", 2) << "\n";
        if (has(s, "cut_error_mm"))
            out << "          cut position error " << percentile_pair(s["cut_error_mm"], "mm", 3)
                << "\n";
    }
    return out.str();
}

std::string bed_text(const json& bed) {
    if (bed.value("clear", true)) return "clear";
    std::string t = "not clear: ";
    if (bed.value("job", 0) > 0) {
        t += "job " + std::to_string(bed["job"].get<long>());
        if (has(bed, "name")) t += " (" + text(bed, "name") + ")";
        t += " " + text(bed, "outcome");
    } else {
        t += "not known";
    }
    if (has(bed, "since")) t += " at " + text(bed, "since");
    return t;
}

std::string queue_table(const json& queue) {
    std::ostringstream out;
    out << "bed: " << bed_text(queue.value("bed", json::object()));
    if (!queue.value("bed", json::object()).value("clear", true))
        out << "  (`fibrecell clear` once the part is off)";
    out << "\nqueue: " << (text(queue, "auto_start") == "after_clear" ? "starts after a clear" : "started by hand (`fibrecell queue next`)");
    if (queue.value("paused", false))
        out << ", paused" << (has(queue, "paused_reason") ? ": " + text(queue, "paused_reason") : "")
            << " (`fibrecell queue resume`)";
    out << "\n";
    const json jobs = queue.value("jobs", json::array());
    if (jobs.empty()) {
        out << "  (empty)\n";
        return out.str();
    }
    out << "  pos  job  name                  state\n";
    for (const json& j : jobs) {
        std::string name = text(j, "name");
        if (name.size() > 20) name = name.substr(0, 19) + "~";
        out << "  " << std::setw(3) << static_cast<long>(number(j, "position")) << "  " << std::setw(3)
            << static_cast<long>(number(j, "id")) << "  " << std::left << std::setw(20) << name
            << std::right << "  " << text(j, "state") << "\n";
    }
    return out.str();
}

std::string live_line(const json& job, const json& cell) {
    const std::string state = text(job, "state");
    if (has(job, "planning"))
        return "planning " + progress_bar(number(job["planning"], "fraction")) + " " +
               text(job["planning"], "stage");
    if (!has(job, "print")) return state;
    const json& p = job["print"];
    std::string line = state + " layer " + std::to_string(static_cast<int>(number(p, "layer"))) +
                       "/" + std::to_string(static_cast<int>(number(p, "layers"))) + " " +
                       progress_bar(number(p, "fraction")) + " " +
                       fixed(100 * number(p, "fraction"), 0) + "%";
    const std::string temps = temperatures(cell);
    if (!temps.empty()) line += "  " + temps;
    line += "  " + duration_text(number(p, "elapsed_s"));
    if (has(p, "eta_s")) line += " ETA " + duration_text(number(p, "eta_s"));
    if (has(cell, "sync") && has(cell["sync"], "cut_error_mm"))
        line += "  cut p99 " + fixed(number(cell["sync"]["cut_error_mm"], "p99"), 3) + " mm";
    return line;
}

std::string outcome_line(const json& job) {
    const std::string state = text(job, "state");
    std::string line = name_of(job) + " " + state;
    if (has(job, "reason")) return line + ": " + text(job, "reason");
    if (state != "completed") return line;
    std::vector<std::string> parts;
    if (has(job, "plan")) {
        const json& p = job["plan"];
        parts.push_back(std::to_string(static_cast<int>(number(p, "layers"))) + " layers");
        parts.push_back("fibre " + fixed(number(p, "fibre_length_m"), 2) + " m");
        parts.push_back("PLA " + fixed(number(p, "pla_length_m"), 2) + " m");
        parts.push_back(std::to_string(static_cast<int>(number(p, "modules"))) + " RAPID modules");
    }
    if (has(job, "result")) {
        const json& r = job["result"];
        if (has(r, "robot_time_s"))
            parts.push_back("print time " + duration_text(number(r, "robot_time_s")) +
                            (has(r, "time_scale") && number(r, "time_scale") != 1
                                 ? " simulated (" + duration_text(number(r, "elapsed_s")) + " real)"
                                 : ""));
        if (has(r, "cut_error_mm"))
            parts.push_back("cut position error " + percentile_pair(r["cut_error_mm"], "mm", 3));
    }
    for (std::size_t i = 0; i < parts.size(); ++i) line += (i == 0 ? ": " : ", ") + parts[i];
    return line;
}

}  // namespace fibrecell::tools
