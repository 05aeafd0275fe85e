#pragma once
// How the client shows the service's answers to a person: job rows, a job's details, the cell,
// live progress for `watch`, and the one-line outcome. Pure functions of the JSON the service
// sends (docs/service.md has the fields); missing fields are left out, never guessed.

#include <nlohmann/json.hpp>

#include <string>

namespace fibrecell::tools {

// "[#########-----------]" with `width` cells; fraction clamped to 0..1.
std::string progress_bar(double fraction, int width = 20);
// 75 -> "1m15s", 3725 -> "1h02m05s", 9.4 -> "9s".
std::string duration_text(double seconds);

// Header and one row per job for `fibrecell jobs`.
std::string jobs_table(const nlohmann::json& jobs);
// Several lines for `fibrecell status JOB`.
std::string job_details(const nlohmann::json& job);
// Several lines for `fibrecell status` (devices, temperatures, current job, sync figures).
std::string cell_details(const nlohmann::json& cell);
// The bed in one phrase: "clear", or "not clear: job 4 (bar) completed at ...".
std::string bed_text(const nlohmann::json& bed);
// `fibrecell queue`: the bed, the start mode and pause, and one row per queued job.
std::string queue_table(const nlohmann::json& queue);
// The live line of `watch`: planning stage and its bar, or layer i/N, the print bar, the
// temperatures, elapsed/ETA and the sync error; empty when there is nothing to show.
std::string live_line(const nlohmann::json& job, const nlohmann::json& cell);
// "job 3 (loop) completed: ..." with the result figures, or the reason of a failure.
std::string outcome_line(const nlohmann::json& job);

// A state after which a job changes no more by itself.
bool is_final_state(const std::string& state);

}  // namespace fibrecell::tools
