#pragma once
// Events the service publishes to subscribed clients as JSON-RPC notifications (no id).
// Topics: a job id for that job's events, "cell" for cell status, "log" for log lines, "queue"
// for the print queue and the bed, "history" for the history's new records, "spools" for the
// spools; a client subscribed to "*" gets every topic.

#include <nlohmann/json.hpp>

#include <string>

namespace fibrecell::api {

namespace notify {
inline constexpr const char* job_state = "notify.job_state";        // in order, immediately
inline constexpr const char* job_progress = "notify.job_progress";  // latest only, rate-limited
inline constexpr const char* cell_status = "notify.cell_status";    // latest only, rate-limited
inline constexpr const char* log = "notify.log";                    // in order, immediately
inline constexpr const char* queue = "notify.queue";                // in order, immediately
inline constexpr const char* history = "notify.history";            // in order, immediately
inline constexpr const char* spools = "notify.spools";              // in order, immediately
}  // namespace notify

namespace topic {
inline constexpr const char* all = "*";
inline constexpr const char* cell = "cell";
inline constexpr const char* log = "log";
inline constexpr const char* queue = "queue";
inline constexpr const char* history = "history";
inline constexpr const char* spools = "spools";
}  // namespace topic

enum class Delivery {
    // Every event, in publishing order, as soon as possible (state changes, log lines). Before one
    // goes out, a held latest-only event of the same topic is flushed so order stays true.
    every,
    // Per client and per (topic, method) at most api.progress_rate_hz; in between only the newest
    // is held and it is always delivered when the interval ends (progress, periodic status).
    latest,
};

struct ApiEvent {
    std::string topic;   // job id, "cell", "log", "queue", "history", "spools"
    std::string method;  // notify.*
    nlohmann::json params = nlohmann::json::object();
    Delivery delivery = Delivery::every;
};

}  // namespace fibrecell::api
