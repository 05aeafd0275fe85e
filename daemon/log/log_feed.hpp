#pragma once
// The service's log lines as API events (topic "log", notify.log: {time, level, text}) for the
// dashboard's log page. One sink on the process's logger, installed once; a service points it
// at its API while it runs. Lines below info are not sent.

#include <nlohmann/json.hpp>

#include <functional>

namespace fibrecell::daemon::logs {

using LogTarget = std::function<void(nlohmann::json line)>;

// Where the log lines go from now on (an empty target: nowhere). The target is called with the
// logger's lock held: it must not log, and must be quick (ApiServer::publish only posts).
void feed_log_to(LogTarget target);

}  // namespace fibrecell::daemon::logs
