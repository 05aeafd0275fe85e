#pragma once
// Time stamps in files people read (state.json, manifest.json).

#include <chrono>
#include <string>

namespace fibrecell::config {

// Now, UTC, ISO 8601 to the second ("2026-12-01T16:30:00Z").
std::string utc_now();
// The same for any instant (an age limit: now minus so many days).
std::string utc_at(std::chrono::system_clock::time_point t);

}  // namespace fibrecell::config
