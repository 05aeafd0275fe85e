#include "daemon/jobs/job_record.hpp"

namespace fibrecell::daemon::jobs {
namespace {

template <class T>
T field(const nlohmann::json& j, const char* key) {
    if (!j.contains(key)) throw StateFileError(std::string(key) + ": missing");
    try {
        return j.at(key).get<T>();
    } catch (const nlohmann::json::exception&) {
        throw StateFileError(std::string(key) + ": wrong type (" + j.at(key).type_name() + ")");
    }
}

}  // namespace

nlohmann::json to_json(const JobRecord& r) {
    return {{"format", std::string(job_state_format)},
            {"id", r.id},
            {"name", r.name},
            {"state", std::string(to_string(r.state))},
            {"reason", r.reason},
            {"submitted_at", r.submitted_at},
            {"updated_at", r.updated_at},
            {"plan_attempts", r.plan_attempts},
            {"start_when_planned", r.start_when_planned},
            {"last_confirmed_event", r.last_confirmed_event},
            {"journal_lost", r.journal_lost},
            {"submitted_by", r.submitted_by},
            {"started_by", r.started_by},
            {"planned_at", r.planned_at},
            {"started_at", r.started_at},
            {"ended_at", r.ended_at}};
}

JobRecord record_from_json(const nlohmann::json& j) {
    if (!j.is_object()) throw StateFileError("not a JSON object");
    const auto format = field<std::string>(j, "format");
    if (format != job_state_format)
        throw StateFileError("format: expected '" + std::string(job_state_format) + "', got '" +
                             format + "'");
    JobRecord r;
    r.id = field<std::int64_t>(j, "id");
    if (r.id < 1) throw StateFileError("id: must be positive");
    r.name = field<std::string>(j, "name");
    try {
        r.state = parse_job_state(field<std::string>(j, "state"));
    } catch (const std::invalid_argument& e) {
        throw StateFileError(std::string("state: ") + e.what());
    }
    r.reason = field<std::string>(j, "reason");
    r.submitted_at = field<std::string>(j, "submitted_at");
    r.updated_at = field<std::string>(j, "updated_at");
    r.plan_attempts = field<int>(j, "plan_attempts");
    r.start_when_planned = field<bool>(j, "start_when_planned");
    r.last_confirmed_event = field<std::int64_t>(j, "last_confirmed_event");
    r.journal_lost = j.contains("journal_lost") && field<bool>(j, "journal_lost");
    for (auto [key, value] : {std::pair{"submitted_by", &r.submitted_by}, {"started_by", &r.started_by},
                              {"planned_at", &r.planned_at}, {"started_at", &r.started_at},
                              {"ended_at", &r.ended_at}})
        if (j.contains(key)) *value = field<std::string>(j, key);
    return r;
}

}  // namespace fibrecell::daemon::jobs
