#include "daemon/queue/queue_state.hpp"

#include "config/durable_file.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fibrecell::daemon::queue {

using nlohmann::json;

json to_json(const QueueState& s) {
    json bed = {{"clear", s.bed.clear}};
    if (!s.bed.clear) {
        bed["job"] = s.bed.job;
        bed["outcome"] = s.bed.outcome;
        bed["since"] = s.bed.since;
    }
    json j = {{"jobs", s.jobs}, {"paused", s.paused}, {"bed", bed}};
    if (!s.paused_reason.empty()) j["paused_reason"] = s.paused_reason;
    return j;
}

QueueState load_queue_state(const std::filesystem::path& file) {
    QueueState s;
    std::ifstream in(file);
    if (!in) {
        if (!std::filesystem::exists(file)) return s;
        throw std::runtime_error(file.string() + ": cannot be read");
    }
    std::ostringstream text;
    text << in.rdbuf();
    try {
        const json j = json::parse(text.str());
        for (const json& id : j.at("jobs")) {
            if (id.get<std::int64_t>() <= 0) throw std::invalid_argument("a job id is not positive");
            s.jobs.push_back(id.get<std::int64_t>());
        }
        s.paused = j.at("paused").get<bool>();
        s.paused_reason = j.value("paused_reason", "");
        const json& bed = j.at("bed");
        s.bed.clear = bed.at("clear").get<bool>();
        if (!s.bed.clear) {
            s.bed.job = bed.at("job").get<std::int64_t>();
            s.bed.outcome = bed.at("outcome").get<std::string>();
            s.bed.since = bed.at("since").get<std::string>();
            if (s.bed.job < 0) throw std::invalid_argument("the bed's job is negative");
        }
    } catch (const std::exception& e) {
        throw std::runtime_error(file.string() + ": not a queue file (" + e.what() + ")");
    }
    return s;
}

void save_queue_state(const std::filesystem::path& file, const QueueState& s) {
    config::write_file_durably(file, to_json(s).dump(2) + "\n");
}

}  // namespace fibrecell::daemon::queue
