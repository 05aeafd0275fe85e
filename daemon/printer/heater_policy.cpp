#include "daemon/printer/heater_policy.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace fibrecell::daemon::printer {

namespace {

std::string minutes(std::chrono::milliseconds d) {
    const double min = std::chrono::duration<double, std::ratio<60>>(d).count();
    char text[32];
    std::snprintf(text, sizeof text, min == std::floor(min) ? "%.0f min" : "%.2g min", min);
    return text;
}

}  // namespace

HeaterPolicy::HeaterPolicy(HeaterPolicyOptions options, Clock::time_point now)
    : options_(options), since_(now) {}

void HeaterPolicy::printing(std::int64_t job) {
    mode_ = Mode::printing;
    job_ = job;
    sent_ = false;
}

void HeaterPolicy::paused(std::int64_t job, Clock::time_point now) {
    mode_ = Mode::paused;
    job_ = job;
    since_ = now;
    sent_ = false;
}

void HeaterPolicy::ended(std::int64_t job, const std::string& outcome, Clock::time_point now) {
    mode_ = Mode::held;
    job_ = job;
    outcome_ = outcome;
    since_ = now;
    sent_ = false;
}

void HeaterPolicy::observe(bool heating, Clock::time_point now) {
    // The board reports its targets once a second: the reports just after the off was sent
    // still show the old ones.
    if (heating && off_sent_at_ && now - *off_sent_at_ < std::chrono::seconds(3)) heating = false;
    heating_ = heating;
    if (!heating) idle_heating_since_.reset();
    else if (!idle_heating_since_) idle_heating_since_ = now;
}

std::optional<HeaterPolicy::Clock::time_point> HeaterPolicy::off_at() const {
    switch (mode_) {
        case Mode::printing: return std::nullopt;
        case Mode::paused: return sent_ ? std::nullopt : std::optional(since_ + options_.paused_timeout);
        case Mode::held: return sent_ ? std::nullopt : std::optional(since_ + options_.hold_after_print);
        case Mode::idle:
            if (!heating_ || !idle_heating_since_) return std::nullopt;
            return *idle_heating_since_ + options_.idle_timeout;
    }
    return std::nullopt;
}

std::optional<std::string> HeaterPolicy::due(Clock::time_point now) const {
    const auto at = off_at();
    if (!at || now < *at) return std::nullopt;
    const std::string job = "job " + std::to_string(job_);
    switch (mode_) {
        case Mode::paused: return job + " paused for " + minutes(options_.paused_timeout);
        case Mode::held:
            return options_.hold_after_print.count() == 0
                       ? job + " " + outcome_
                       : job + " " + outcome_ + " " + minutes(options_.hold_after_print) +
                             " ago (print.heater_hold_min)";
        case Mode::idle:
            return "no job on the cell for " + minutes(options_.idle_timeout) +
                   " with a heater on (print.idle_heater_timeout_min)";
        case Mode::printing: break;
    }
    return std::nullopt;
}

void HeaterPolicy::switched_off(const std::string& reason, Clock::time_point now) {
    last_off_ = reason;
    off_sent_at_ = now;
    heating_ = false;
    idle_heating_since_.reset();
    if (mode_ == Mode::paused) {
        sent_ = true;  // the job keeps the cell; its resume heats them again
    } else {
        mode_ = Mode::idle;
        since_ = now;
    }
}

nlohmann::json HeaterPolicy::status(Clock::time_point now) const {
    nlohmann::json s = {{"on", heating_}, {"why", nullptr}, {"off_in_s", nullptr},
                        {"last_off", last_off_.empty() ? nlohmann::json() : nlohmann::json(last_off_)}};
    if (heating_) {
        const std::string job = "job " + std::to_string(job_);
        switch (mode_) {
            case Mode::printing: s["why"] = "printing " + job; break;
            case Mode::paused: s["why"] = job + " is paused"; break;
            case Mode::held: s["why"] = "kept hot after " + job + " " + outcome_; break;
            case Mode::idle: s["why"] = "on with no job on the cell"; break;
        }
    }
    if (const auto at = off_at())
        s["off_in_s"] = std::max(0.0, std::chrono::duration<double>(*at - now).count());
    return s;
}

}  // namespace fibrecell::daemon::printer
