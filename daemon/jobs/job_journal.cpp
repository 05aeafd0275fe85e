#include "daemon/jobs/job_journal.hpp"

#include "config/durable_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

namespace fibrecell::daemon::jobs {
namespace {

std::string event_line(const JournalEvent& e, const char* phase) {
    nlohmann::json j{{"seq", e.sequence},
                     {"kind", std::string(to_string(e.kind))},
                     {"layer", e.layer},
                     {"path", e.path},
                     {"phase", phase}};
    return j.dump();
}

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw JournalError(path.string() + ": cannot read");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

JournalSummary read_journal(const std::filesystem::path& path) {
    JournalSummary s;
    if (!std::filesystem::exists(path)) return s;
    const std::string text = read_text(path);
    std::size_t start = 0;
    int line = 0;
    while (start < text.size()) {
        ++line;
        const std::size_t end = text.find('\n', start);
        const bool complete = end != std::string::npos;
        const std::string record = text.substr(start, complete ? end - start : std::string::npos);
        start = complete ? end + 1 : text.size();
        const bool last = start >= text.size();
        nlohmann::json j = nlohmann::json::parse(record, nullptr, false);
        const bool valid =
            complete && j.is_object() && j.contains("phase") && j["phase"].is_string();
        if (!valid) {
            if (last) {  // a crash in the middle of the last append
                s.torn_tail = true;
                break;
            }
            throw JournalError(path.string() + ": line " + std::to_string(line) +
                               ": not a journal record");
        }
        const std::string phase = j["phase"].get<std::string>();
        if (phase == "sending" || phase == "confirmed") {
            if (!j.contains("seq") || !j["seq"].is_number_integer() ||
                j["seq"].get<long long>() < 1)
                throw JournalError(path.string() + ": line " + std::to_string(line) +
                                   ": seq must be a positive integer");
            const std::int64_t seq = j["seq"].get<std::int64_t>();
            std::int64_t& high = phase == "sending" ? s.last_sent : s.last_confirmed;
            high = std::max(high, seq);
        } else if (phase == "fed") {
            if (!j.contains("seq") || !j["seq"].is_number_integer() ||
                j["seq"].get<long long>() < 1 || !j.contains("mm") || !j["mm"].is_number() ||
                !(j["mm"].get<double>() >= 0))
                throw JournalError(path.string() + ": line " + std::to_string(line) +
                                   ": a fed record needs a positive integer seq and mm >= 0");
            s.fed = JournalFed{j["seq"].get<std::int64_t>(), j["mm"].get<double>()};
        } else if (phase != "resume") {
            throw JournalError(path.string() + ": line " + std::to_string(line) +
                               ": unknown phase '" + phase + "'");
        }
        ++s.records;
    }
    return s;
}

void repair_journal(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) return;
    const std::string text = read_text(path);
    const std::size_t keep = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
    if (keep == text.size()) {
        // Complete lines only; a torn last line that still ends in '\n' cannot happen (one write).
        return;
    }
    std::filesystem::resize_file(path, keep);
}

JobJournal::JobJournal(const std::filesystem::path& path, const JournalSummary& summary)
    : file_(std::make_unique<config::DurableAppender>(path)), summary_(summary) {}

JobJournal::~JobJournal() = default;

void JobJournal::sending(const JournalEvent& e) {
    std::lock_guard lock(mu_);
    file_->append(event_line(e, "sending"));
    summary_.last_sent = std::max(summary_.last_sent, e.sequence);
    ++summary_.records;
}

void JobJournal::confirmed(const JournalEvent& e) {
    std::lock_guard lock(mu_);
    file_->append(event_line(e, "confirmed"));
    summary_.last_confirmed = std::max(summary_.last_confirmed, e.sequence);
    ++summary_.records;
}

void JobJournal::resumed(std::int64_t first_event) {
    std::lock_guard lock(mu_);
    file_->append(nlohmann::json{{"phase", "resume"}, {"first_event", first_event}}.dump());
    ++summary_.records;
}

void JobJournal::fed(const JournalFed& f) {
    std::lock_guard lock(mu_);
    file_->append(nlohmann::json{{"seq", f.sequence}, {"phase", "fed"}, {"mm", f.mm}}.dump());
    summary_.fed = f;
    ++summary_.records;
}

std::optional<JournalFed> JobJournal::last_fed() const {
    std::lock_guard lock(mu_);
    return summary_.fed;
}

std::int64_t JobJournal::last_sent() const {
    std::lock_guard lock(mu_);
    return summary_.last_sent;
}

std::int64_t JobJournal::last_confirmed() const {
    std::lock_guard lock(mu_);
    return summary_.last_confirmed;
}

}  // namespace fibrecell::daemon::jobs
