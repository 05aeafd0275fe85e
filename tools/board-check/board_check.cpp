#include "tools/board-check/board_check.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace fibrecell::tools {

namespace {

using Json = nlohmann::json;

Json read_json(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("board-check: cannot read " + path);
    try {
        return Json::parse(in);
    } catch (const std::exception& e) {
        throw std::runtime_error("board-check: " + path + " is not JSON: " + e.what());
    }
}

// One extruder's step pulses as runs: consecutive steps in one direction with no cut between.
struct Run {
    bool forward = true;
    long steps = 0;
};

struct Extruder {
    bool enabled = false, dir = false;
    std::vector<Run> runs;
    bool cut_since_last = false;
    void step(bool forward, bool split) {
        if (runs.empty() || runs.back().forward != forward || split) runs.push_back({forward, 0});
        ++runs.back().steps;
    }
};

}  // namespace

BoardCheck check_board(const std::string& plan_dir, const std::string& edge_log,
                       const BoardCheckOptions& o) {
    const Json program = read_json(plan_dir + "/program.json");
    const Json print = read_json(plan_dir + "/print.json");
    const Json& board = print.at("board");
    const int pla_tool = board.at("pla_tool"), ccf_tool = board.at("ccf_tool");
    const double thread_mm = board.at("thread_feed_mm"), pla_e_per_mm = board.at("pla_e_per_path_mm");
    if (pla_tool < 0 || pla_tool > 1 || ccf_tool < 0 || ccf_tool > 1 || pla_tool == ccf_tool)
        throw std::runtime_error("board-check: print.json's tools are not T0 and T1");

    BoardCheck r;
    std::vector<PathFeed> fibre, pla;
    const Json& cols = program.at("event_columns");
    const auto col = [&](const char* name) {
        for (std::size_t i = 0; i < cols.size(); ++i)
            if (cols[i] == name) return i;
        throw std::runtime_error(std::string("board-check: program.json has no event column ") + name);
    };
    const std::size_t kind = col("kind"), layer = col("layer"), path = col("path"), length = col("length_mm");
    for (const Json& e : program.at("events")) {
        const std::string k = e.at(kind);
        const PathFeed p{k == "fibre_start" ? "fibre" : "pla", e.at(layer).get<int>(), e.at(path).get<int>(),
                         0, 0};
        if (k == "fibre_start") {
            fibre.push_back(p);
            fibre.back().planned_mm = thread_mm + e.at(length).get<double>();
        } else if (k == "extrude_on") {
            pla.push_back(p);
            pla.back().planned_mm = e.at(length).get<double>() * pla_e_per_mm;
        } else if (k == "cut") {
            ++r.planned_cuts;
        }
    }

    std::ifstream in(edge_log, std::ios::binary);
    if (!in) throw std::runtime_error("board-check: cannot read " + edge_log);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.erase(text.rfind('\n') + 1);  // a last line still being written is not read
    std::istringstream lines(text);
    Extruder ex[2];
    std::string line;
    std::size_t number = 0;
    while (std::getline(lines, line)) {
        ++number;
        std::istringstream fields(line);
        double t = 0;
        std::string pin;
        int level = 0;
        if (!(fields >> t >> pin >> level))
            throw std::runtime_error("board-check: " + edge_log + " line " + std::to_string(number) +
                                     ": not '<s> <pin> <0|1>'");
        const bool high = level != 0;
        if (pin.size() > 3 && pin[0] == 'e' && (pin[1] == '0' || pin[1] == '1') && pin[2] == '_') {
            Extruder& x = ex[pin[1] - '0'];
            const std::string what = pin.substr(3);
            if (what == "enable") x.enabled = !high;  // active low
            else if (what == "dir") x.dir = high;
            else if (what == "step" && high) {
                if (!x.enabled) {
                    ++r.steps_while_disabled;
                    continue;
                }
                x.step(x.dir != o.invert_e_dir, x.cut_since_last);
                x.cut_since_last = false;
            }
        } else if (pin == "d11" && high) {
            ++r.cuts;
            ex[ccf_tool].cut_since_last = true;  // the next fibre steps are the next path's
        }
    }

    // Fibre: one forward run per path (a run ends at a cut).
    const std::vector<Run>& fruns = ex[ccf_tool].runs;
    for (const Run& run : fruns)
        if (!run.forward) r.problems.push_back("the fibre extruder ran backwards");
    r.fibre_runs = static_cast<int>(fruns.size());
    for (std::size_t i = 0; i < fibre.size(); ++i)
        if (i < fruns.size()) fibre[i].fed_mm = fruns[i].steps / o.steps_per_mm;
    // PLA: forward run (prime + path), backward run (retract); the difference is the path.
    const std::vector<Run>& pruns = ex[pla_tool].runs;
    std::vector<double> pla_fed;
    for (std::size_t i = 0; i < pruns.size(); ++i) {
        if (!pruns[i].forward) continue;
        const long back = i + 1 < pruns.size() && !pruns[i + 1].forward ? pruns[i + 1].steps : 0;
        pla_fed.push_back((pruns[i].steps - back) / o.steps_per_mm);
    }
    r.pla_runs = static_cast<int>(pla_fed.size());
    for (std::size_t i = 0; i < pla.size(); ++i)
        if (i < pla_fed.size()) pla[i].fed_mm = pla_fed[i];

    r.planned_fibre_paths = static_cast<int>(fibre.size());
    r.planned_pla_paths = static_cast<int>(pla.size());
    for (auto* list : {&pla, &fibre})
        for (const PathFeed& p : *list) {
            r.paths.push_back(p);
            r.worst_error = std::max(r.worst_error, std::abs(p.error()));
            if (std::abs(p.error()) > o.tolerance) {
                std::ostringstream s;
                s << p.kind << " path " << p.path << " of layer " << p.layer << ": fed " << p.fed_mm
                  << " mm, planned " << p.planned_mm << " mm";
                r.problems.push_back(s.str());
            }
        }
    if (r.fibre_runs != r.planned_fibre_paths)
        r.problems.push_back(std::to_string(r.fibre_runs) + " fibre feeds for " +
                             std::to_string(r.planned_fibre_paths) + " planned fibre paths");
    if (r.pla_runs != r.planned_pla_paths)
        r.problems.push_back(std::to_string(r.pla_runs) + " PLA feeds for " +
                             std::to_string(r.planned_pla_paths) + " planned PLA paths");
    if (r.cuts != r.planned_cuts)
        r.problems.push_back(std::to_string(r.cuts) + " cuts for " + std::to_string(r.planned_cuts) +
                             " planned");
    if (r.steps_while_disabled > 0)
        r.problems.push_back(std::to_string(r.steps_while_disabled) + " step pulses with the driver off");
    return r;
}

}  // namespace fibrecell::tools
