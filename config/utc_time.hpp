#pragma once
// Time stamps in files people read (state.json, manifest.json).

#include <string>

namespace fibrecell::config {

// Now, UTC, ISO 8601 to the second ("2026-12-01T16:30:00Z").
std::string utc_now();

}  // namespace fibrecell::config
