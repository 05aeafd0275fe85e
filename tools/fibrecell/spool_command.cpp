#include "tools/fibrecell/spool_command.hpp"

#include "tools/fibrecell/service_connection.hpp"

#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace fibrecell::tools {
namespace {

using nlohmann::json;

// A number and a unit from `units` (each with its factor), e.g. "250m".
double with_unit(const std::string& text, std::initializer_list<std::pair<const char*, double>> units,
                 const char* what) {
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        throw std::invalid_argument(std::string(what) + " '" + text + "' is not a number with a unit");
    }
    std::string unit = text.substr(used);
    unit.erase(0, unit.find_first_not_of(' '));
    std::string known;
    for (const auto& [name, factor] : units) {
        if (unit == name) {
            if (!(v > 0)) throw std::invalid_argument(std::string(what) + " '" + text + "' must be more than 0");
            return v * factor;
        }
        known += known.empty() ? name : std::string(", ") + name;
    }
    throw std::invalid_argument(std::string(what) + " '" + text + "' needs a unit: " + known);
}

std::string spool_table(const json& answer) {
    std::ostringstream out;
    for (const json& s : answer["spools"]) {
        out << s.value("tool", "") << " (" << s.value("role", "") << "): ";
        if (!s.value("loaded", false)) {
            out << "no spool loaded (not checked)\n";
            continue;
        }
        char left[96];
        std::snprintf(left, sizeof left, "%.2f m left of %.2f m", s.value("remaining_m", 0.0),
                      s.value("loaded_m", 0.0));
        out << s.value("material", "") << (s.value("lot", "").empty() ? "" : ", lot " + s.value("lot", ""))
            << ": " << left << " (loaded " << s.value("loaded_at", "") << ")\n";
    }
    const json& q = answer["queue_needs"];
    char needs[160];
    std::snprintf(needs, sizeof needs, "the queue (%d jobs) needs %.2f m of fibre and %.2f m of PLA",
                  q.value("jobs", 0), q.value("fibre_m", 0.0), q.value("pla_m", 0.0));
    out << needs;
    if (q.value("still_planning", 0) > 0) out << " (" << q.value("still_planning", 0) << " still planning)";
    out << "; a start needs the plan's figure + " << answer.value("margin_percent", 0.0) << "% + "
        << answer.value("margin_m", 0.0) << " m (spools.check: " << answer.value("check", "") << ")\n";
    if (answer.contains("note")) out << "note: " << answer.value("note", "") << "\n";
    return out.str();
}

}  // namespace

double length_mm(const std::string& text) {
    return with_unit(text, {{"mm", 1.0}, {"m", 1000.0}, {"km", 1e6}}, "length");
}

double mass_g(const std::string& text) { return with_unit(text, {{"g", 1.0}, {"kg", 1000.0}}, "mass"); }

void add_spool_command(CLI::App& app, int& exit_code) {
    auto* spool = app.add_subcommand("spool", "the spools on the hotends (without a verb: show them)");
    auto c = std::make_shared<Connection>();
    add_connection_options(*spool, *c);

    struct Load {
        std::string tool, material, length, mass, tow, lot;
        double density = 0, diameter = 0;
    };
    auto l = std::make_shared<Load>();
    auto lc = std::make_shared<Connection>();
    auto* load = spool->add_subcommand("load", "a new spool on a hotend (T0 PLA, T1 fibre)");
    load->add_option("tool", l->tool, "T0 or T1")->required();
    load->add_option("--material", l->material, "\"PLA\", \"CF 1K\"")->required();
    auto* length = load->add_option("--length", l->length, "what is on it: 250m, 2500mm");
    auto* mass = load->add_option("--mass", l->mass, "or its mass: 500g, 1kg (with --density and --diameter)");
    length->excludes(mass);
    load->add_option("--density", l->density, "g/cm3, with --mass (PLA 1.24)");
    load->add_option("--diameter", l->diameter, "filament diameter [mm]");
    load->add_option("--tow", l->tow, "fibre tow: 1K, 3K");
    load->add_option("--lot", l->lot, "the spool's lot");
    add_connection_options(*load, *lc);
    load->callback([&exit_code, lc, l] {
        guarded(exit_code, [&] {
            json params = {{"tool", l->tool}, {"material", l->material}};
            if (!l->length.empty()) params["length_mm"] = length_mm(l->length);
            if (!l->mass.empty()) params["mass_g"] = mass_g(l->mass);
            if (l->density > 0) params["density_g_cm3"] = l->density;
            if (l->diameter > 0) params["diameter_mm"] = l->diameter;
            if (!l->tow.empty()) params["tow"] = l->tow;
            if (!l->lot.empty()) params["lot"] = l->lot;
            api::ApiClient client = lc->connect();
            const json answer = client.call("spool.load", params);
            print(*lc, answer, spool_table(answer));
            return 0;
        });
    });

    auto tool = std::make_shared<std::string>();
    auto uc = std::make_shared<Connection>();
    auto* unload = spool->add_subcommand("unload", "no spool on the hotend any more (not checked)");
    unload->add_option("tool", *tool, "T0 or T1")->required();
    add_connection_options(*unload, *uc);
    unload->callback([&exit_code, uc, tool] {
        guarded(exit_code, [&] {
            api::ApiClient client = uc->connect();
            const json answer = client.call("spool.unload", {{"tool", *tool}});
            print(*uc, answer, spool_table(answer));
            return 0;
        });
    });

    spool->callback([&exit_code, c, spool] {
        if (!spool->get_subcommands().empty()) return;  // a verb ran
        guarded(exit_code, [&] {
            api::ApiClient client = c->connect();
            const json answer = client.call("spool.list");
            print(*c, answer, spool_table(answer));
            return 0;
        });
    });
}

}  // namespace fibrecell::tools
