#include "daemon/spools/spool_state.hpp"

#include "config/durable_file.hpp"

#include <fstream>
#include <stdexcept>

namespace fibrecell::daemon::spools {

using nlohmann::json;

namespace {

constexpr const char* format = "fibrecell.spools/1";

double number(const json& j, const char* key) {
    if (!j.contains(key) || !j[key].is_number())
        throw std::invalid_argument(std::string(key) + ": expected a number");
    return j[key].get<double>();
}

}  // namespace

json to_json(const SpoolState& s) {
    json spools = json::object();
    for (const auto& [tool, sp] : s.spools)
        spools[tool] = {{"material", sp.material},
                        {"tow", sp.tow},
                        {"lot", sp.lot},
                        {"diameter_mm", sp.diameter_mm ? json(*sp.diameter_mm) : json(nullptr)},
                        {"loaded_at", sp.loaded_at},
                        {"loaded_mm", sp.loaded_mm},
                        {"used_mm", sp.used_mm}};
    return {{"format", format},
            {"spools", spools},
            {"charged",
             {{"job", s.charged.job},
              {"run", s.charged.run},
              {"pla_mm", s.charged.pla_mm},
              {"fibre_mm", s.charged.fibre_mm}}}};
}

SpoolState spool_state_from_json(const json& j) {
    if (!j.is_object() || j.value("format", "") != format)
        throw std::invalid_argument(std::string("format: expected ") + format);
    SpoolState s;
    if (!j.contains("spools") || !j["spools"].is_object())
        throw std::invalid_argument("spools: expected an object");
    for (const auto& [tool, sp] : j["spools"].items()) {
        if (tool != "T0" && tool != "T1")
            throw std::invalid_argument("spools." + tool + ": not a hotend (T0, T1)");
        Spool x;
        x.material = sp.value("material", "");
        x.tow = sp.value("tow", "");
        x.lot = sp.value("lot", "");
        if (sp.contains("diameter_mm") && sp["diameter_mm"].is_number())
            x.diameter_mm = sp["diameter_mm"].get<double>();
        x.loaded_at = sp.value("loaded_at", "");
        x.loaded_mm = number(sp, "loaded_mm");
        x.used_mm = number(sp, "used_mm");
        s.spools[tool] = x;
    }
    if (j.contains("charged") && j["charged"].is_object()) {
        const json& c = j["charged"];
        s.charged = {c.value("job", std::int64_t{0}), c.value("run", std::uint64_t{0}),
                     number(c, "pla_mm"), number(c, "fibre_mm")};
    }
    return s;
}

SpoolState read_spools(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) return {};
    try {
        return spool_state_from_json(json::parse(in));
    } catch (const std::exception& e) {
        throw std::runtime_error(file.string() + ": " + e.what());
    }
}

void write_spools(const std::filesystem::path& file, const SpoolState& s) {
    config::write_file_durably(file, to_json(s).dump(2) + "\n");
}

}  // namespace fibrecell::daemon::spools
