#include "daemon/jobs/job_journal.hpp"

#include "config/durable_file.hpp"
#include "config/thread_priority.hpp"

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

std::string read_journal_text(const std::filesystem::path& path) {
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
    const std::string text = read_journal_text(path);
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
            if (phase == "confirmed" && j.value("kind", "") == "layer_end")
                s.layers_done = std::max(s.layers_done, j.value("layer", -1) + 1);
        } else if (phase == "fed") {
            if (!j.contains("seq") || !j["seq"].is_number_integer() ||
                j["seq"].get<long long>() < 1 || !j.contains("mm") || !j["mm"].is_number() ||
                !(j["mm"].get<double>() >= 0))
                throw JournalError(path.string() + ": line " + std::to_string(line) +
                                   ": a fed record needs a positive integer seq and mm >= 0");
            s.fed = JournalFed{j["seq"].get<std::int64_t>(), j["mm"].get<double>()};
        } else if (phase == "used") {
            const auto mm = [&](const char* key) {
                if (!j.contains(key) || !j[key].is_number())
                    throw JournalError(path.string() + ": line " + std::to_string(line) +
                                       ": a used record needs pla_mm and fibre_mm");
                return j[key].get<double>();
            };
            s.used = JournalUsed{mm("pla_mm"), mm("fibre_mm")};
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
    const std::string text = read_journal_text(path);
    const std::size_t keep = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
    if (keep == text.size()) {
        // Complete lines only; a torn last line that still ends in '\n' cannot happen (one write).
        return;
    }
    std::filesystem::resize_file(path, keep);
}

JobJournal::JobJournal(const std::filesystem::path& path, const JournalSummary& summary)
    : file_(std::make_unique<config::DurableAppender>(path)), summary_(summary) {}

JobJournal::~JobJournal() {
    {
        std::lock_guard lock(mu_);
        stopping_ = true;
    }
    wake_.notify_all();
    if (writer_.joinable()) writer_.join();  // the writer leaves once the queue is empty
}

// The caller holds mu_. The writer starts with the first queued record: a store holds the
// journals of every job, most of which never get one.
void JobJournal::queue(std::string line) {
    queued_.push_back(std::move(line));
    ++queued_count_;
    if (!writer_.joinable())
        writer_ = std::thread([this] {
            config::name_this_thread("jobs.journal");
            write_queued();
        });
}

void JobJournal::write_queued() {
    std::unique_lock lock(mu_);
    for (;;) {
        wake_.wait(lock, [&] { return stopping_ || !queued_.empty(); });
        if (queued_.empty()) return;  // stopping, all written
        std::vector<std::string> batch;
        batch.swap(queued_);
        const std::uint64_t upto = queued_count_;
        lock.unlock();
        // One write and one sync for the whole batch (records hold no newline).
        std::string lines;
        for (const std::string& l : batch) lines += (lines.empty() ? "" : "\n") + l;
        std::optional<std::string> failed;
        try {
            append_now(lines);
        } catch (const std::exception& e) {
            failed = e.what();
        }
        lock.lock();
        if (failed) failure_ = failed;
        written_count_ = upto;
        written_.notify_all();
    }
}

void JobJournal::append_now(const std::string& line) {
    std::lock_guard lock(file_mu_);
    file_->append(line);
}

void JobJournal::sending(const JournalEvent& e) {
    flush();
    append_now(event_line(e, "sending"));
    std::lock_guard lock(mu_);
    summary_.last_sent = std::max(summary_.last_sent, e.sequence);
    ++summary_.records;
}

void JobJournal::resumed(std::int64_t first_event) {
    flush();
    append_now(nlohmann::json{{"phase", "resume"}, {"first_event", first_event}}.dump());
    std::lock_guard lock(mu_);
    ++summary_.records;
}

void JobJournal::confirmed(const JournalEvent& e) {
    {
        std::lock_guard lock(mu_);
        queue(event_line(e, "confirmed"));
        summary_.last_confirmed = std::max(summary_.last_confirmed, e.sequence);
        ++summary_.records;
    }
    wake_.notify_one();
}

void JobJournal::fed(const JournalFed& f) {
    {
        std::lock_guard lock(mu_);
        queue(nlohmann::json{{"seq", f.sequence}, {"phase", "fed"}, {"mm", f.mm}}.dump());
        summary_.fed = f;
        ++summary_.records;
    }
    wake_.notify_one();
}

void JobJournal::used(const JournalUsed& u) {
    {
        std::lock_guard lock(mu_);
        queue(nlohmann::json{{"phase", "used"}, {"pla_mm", u.pla_mm}, {"fibre_mm", u.fibre_mm}}.dump());
        summary_.used = u;
        ++summary_.records;
    }
    wake_.notify_one();
}

void JobJournal::flush() {
    std::unique_lock lock(mu_);
    const std::uint64_t target = queued_count_;
    written_.wait(lock, [&] { return written_count_ >= target; });
}

std::optional<std::string> JobJournal::take_failure() {
    std::lock_guard lock(mu_);
    std::optional<std::string> f;
    f.swap(failure_);
    return f;
}

std::int64_t JobJournal::last_sent() const {
    std::lock_guard lock(mu_);
    return summary_.last_sent;
}

std::int64_t JobJournal::last_confirmed() const {
    std::lock_guard lock(mu_);
    return summary_.last_confirmed;
}

std::optional<JournalFed> JobJournal::last_fed() const {
    std::lock_guard lock(mu_);
    return summary_.fed;
}

std::optional<JournalUsed> JobJournal::last_used() const {
    std::lock_guard lock(mu_);
    return summary_.used;
}

}  // namespace fibrecell::daemon::jobs
