#pragma once
// spdlog set up once per process. Event names are stable first tokens ("job.started"); the level
// comes from the caller (config) or the FIBRECELL_LOG environment variable.

#include <string>

namespace fibrecell::config {

// level: trace, debug, info, warn, error, off ("" = info). $FIBRECELL_LOG, when set, overrides it.
// Log lines go to stderr so that stdout stays free for command output.
void setup_logging(const std::string& level = "");

}  // namespace fibrecell::config
