#pragma once
// <state_dir>/spools.json: the spool loaded on each hotend and what has been charged to it, and
// which job's feed was charged last (so that a restart can charge the rest from that job's
// journal). Replaced whole (temp, fsync, rename) at every load and at every layer of a print.
//
//   {"format": "fibrecell.spools/1",
//    "spools": {"T1": {"material": "CF 1K", "tow": "1K", "diameter_mm": null, "lot": "A17",
//                      "loaded_at": "...", "loaded_mm": 250000, "used_mm": 812.5}},
//    "charged": {"job": 12, "run": 1765104000123456, "pla_mm": 3120.4, "fibre_mm": 812.5}}

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace fibrecell::daemon::spools {

struct Spool {
    std::string material, tow, lot;
    std::optional<double> diameter_mm;
    std::string loaded_at;  // UTC, ISO 8601
    double loaded_mm = 0;   // length when it was loaded
    double used_mm = 0;     // fed from it since (net: a retraction gives back)

    double remaining_mm() const { return loaded_mm - used_mm; }
};

// A job's used filament (JournalUsed) as far as the spools were charged with it.
struct Charged {
    std::int64_t job = 0;
    std::uint64_t run = 0;  // PrintRunner::Feed::run
    double pla_mm = 0, fibre_mm = 0;
};

struct SpoolState {
    std::map<std::string, Spool> spools;  // "T0", "T1": the hotends that have one
    Charged charged;
};

nlohmann::json to_json(const SpoolState& s);
// Throws std::invalid_argument naming the key.
SpoolState spool_state_from_json(const nlohmann::json& j);

// A missing file is no spools. Throws std::runtime_error naming the file when it cannot be read.
SpoolState read_spools(const std::filesystem::path& file);
// Throws std::system_error naming the file.
void write_spools(const std::filesystem::path& file, const SpoolState& s);

}  // namespace fibrecell::daemon::spools
