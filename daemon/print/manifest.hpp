#pragma once
// manifest.json of the plan directory: every file of the plan with its size and sha256, and the
// facts of the cell the plan was made for (robot, bed, tools, head, motion and RAPID settings,
// signal names, the extruder's tools, flow and cutter). It is written last, once every other
// file is on the disk; a plan without one is incomplete. The print verifies it before anything
// moves: a file that changed makes the plan damaged, a cell fact that changed makes it outdated,
// and either refuses the start (docs/jobs.md, "The plan is the print").

#include "daemon/cell/cell_config.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::print {

inline constexpr std::string_view manifest_format = "fibrecell.manifest/1";
inline constexpr const char* manifest_name = "manifest.json";

struct ManifestEntry {
    std::string path;  // inside the plan directory, '/'-separated
    std::uint64_t bytes = 0;
    std::string sha256;  // lowercase hex
};

struct Manifest {
    std::string job;
    std::string planned_at;  // UTC, ISO 8601
    nlohmann::json cell;     // cell_facts() at planning
    std::vector<ManifestEntry> files;
};

// A plan that cannot be printed as it is: damaged (files), outdated (cell) or incomplete.
class PlanRefused : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

std::string sha256_hex(std::string_view bytes);
ManifestEntry manifest_entry(std::string path, std::string_view bytes);

// What of the cell configuration a plan depends on, under the cell YAML's key names. Link
// settings (ports, addresses, timeouts), logging and the simulation are not among them.
nlohmann::json cell_facts(const CellConfig& cell);

// "robot.bed.position_mm: [380,-150,100] when planned, [390,-150,100] now" for every fact that
// differs (a fact only one side has counts); empty when the cell is the one planned for.
std::vector<std::string> changed_facts(const nlohmann::json& planned, const nlohmann::json& now);

std::string manifest_json_text(const Manifest& m);
// Reads dir/manifest.json. Throws PlanRefused when it is missing or unreadable.
Manifest read_manifest(const std::filesystem::path& plan_dir);

// Every listed file's size and sha256 against the files in `plan_dir`; one line per problem
// ("rapid/FcChunk0003.mod: sha256 differs from the manifest"), empty when the plan is intact.
std::vector<std::string> verify_files(const std::filesystem::path& plan_dir, const Manifest& m);

// read_manifest + verify_files + changed_facts against `cell`; throws PlanRefused saying what is
// wrong and what to do (replan). Returns the manifest of a plan that may be printed.
Manifest check_plan(const std::filesystem::path& plan_dir, const CellConfig& cell);

}  // namespace fibrecell::daemon::print
