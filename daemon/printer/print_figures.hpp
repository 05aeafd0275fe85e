#pragma once
// What a print's synchronisation says in the job's figures (docs/socket-api.md, docs/jobs.md):
// the live `sync` block of a printing job's status, result.json's timing and shortfalls, and the
// job's reason when its print fell short of the plan.

#include "daemon/sync/sync_status.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace fibrecell::daemon::printer {

// last_confirmed, faulted, paused; the cut position error and the slowest kind's latency once seen.
nlohmann::json live_sync_json(const sync::SyncStatus& s);

// result.json's share: cut_error_mm (once a cut was seen), latency_ms per event kind, shortfalls.
nlohmann::json result_sync_json(const sync::SyncStatus& s);

// "2 shortfalls from the plan: fibre path at event 12 (layer 1, path 3): 4.0 mm not fed; ...":
// the first few, then how many more.
std::string shortfall_reason(const std::vector<sync::Shortfall>& all);

}  // namespace fibrecell::daemon::printer
