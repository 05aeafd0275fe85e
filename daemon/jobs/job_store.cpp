#include "daemon/jobs/job_store.hpp"

#include "config/durable_file.hpp"
#include "config/utc_time.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <random>
#include <sstream>

namespace fibrecell::daemon::jobs {
namespace {

namespace fs = std::filesystem;

constexpr const char* incoming_prefix = ".incoming-";
constexpr const char* removed_prefix = ".removed-";
constexpr const char* lost_journal_text =
    "; its journal.jsonl is missing: resume needs the operator's word (--journal-lost)";

// The job's print had begun, so its journal should be there (it is made before the print starts).
bool had_printed(const JobRecord& r) {
    return r.state == JobState::printing || r.state == JobState::pausing ||
           r.state == JobState::paused ||
           (r.state == JobState::interrupted && r.last_confirmed_event > 0);
}

// A job folder's name: a positive decimal id without leading zeros.
std::optional<std::int64_t> folder_id(const std::string& name) {
    if (name.empty() || name.size() > 18 || name[0] == '0') return std::nullopt;
    for (char c : name)
        if (c < '0' || c > '9') return std::nullopt;
    return std::stoll(name);
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw StateFileError("cannot read");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string unique_suffix() {
    static std::mt19937_64 rng{std::random_device{}()};
    static std::mutex mu;
    std::lock_guard lock(mu);
    std::ostringstream s;
    s << std::hex << rng();
    return s.str();
}

}  // namespace

JobStore::JobStore(JobStoreOptions options) : options_(std::move(options)) {
    fs::create_directories(jobs_root());
}

JobStore::~JobStore() = default;

fs::path JobStore::job_dir(std::int64_t id) const {
    return jobs_root() / std::to_string(id);
}

std::int64_t JobStore::next_id() const {
    std::lock_guard lock(mu_);
    return next_id_;
}

void JobStore::on_change(std::function<void(const JobRecord&)> observer) {
    std::lock_guard lock(mu_);
    observer_ = std::move(observer);
}

void JobStore::notify(const std::vector<JobRecord>& changed) {
    std::function<void(const JobRecord&)> observer;
    {
        std::lock_guard lock(mu_);
        observer = observer_;
    }
    if (!observer) return;
    for (const JobRecord& r : changed) observer(r);
}

JobStore::Entry& JobStore::entry(std::int64_t id) {
    const auto it = jobs_.find(id);
    if (it == jobs_.end()) throw JobNotFound("no job " + std::to_string(id));
    return it->second;
}

const JobStore::Entry& JobStore::entry(std::int64_t id) const {
    const auto it = jobs_.find(id);
    if (it == jobs_.end()) throw JobNotFound("no job " + std::to_string(id));
    return it->second;
}

void JobStore::persist(const JobRecord& r) const {
    config::write_file_durably(job_dir(r.id) / "state.json", to_json(r).dump(2) + "\n");
}

namespace {

// The record's times after a change from `from`: updated now; planned, first printing and ended
// (an interruption too) when it just did.
void stamp(JobRecord& r, JobState from) {
    const std::string now = config::utc_now();
    r.updated_at = now;
    if (r.state == JobState::planned && from == JobState::planning) r.planned_at = now;
    if (r.state == JobState::printing && r.started_at.empty()) r.started_at = now;
    if (is_ended(r.state) || r.state == JobState::interrupted) r.ended_at = now;
}

}  // namespace

JobRecord JobStore::change(Entry& e, JobState to, const std::string& reason) {
    const JobRecord before = e.record;
    JobRecord& r = e.record;
    r.state = to;
    if (!reason.empty() || !keeps_its_reason(to)) r.reason = reason;
    stamp(r, before.state);
    if (e.journal) r.last_confirmed_event = e.journal->last_confirmed();
    try {
        persist(r);
    } catch (const std::exception& x) {
        r = before;  // memory and disk agree: the change did not happen
        throw StateWriteError("job " + std::to_string(r.id) + ": cannot save its state (" +
                              std::string(to_string(to)) + "): " + x.what());
    }
    spdlog::info("job.state job {} {} -> {}{}{}", r.id, to_string(before.state), to_string(to),
                 reason.empty() ? "" : ": ", reason);
    return r;
}

LoadReport JobStore::load_all() {
    LoadReport report;
    std::vector<JobRecord> changed;
    {
        std::lock_guard lock(mu_);
        std::int64_t next = 1;
        const fs::path next_file = options_.state_dir / "next_id";
        if (fs::exists(next_file)) {
            try {
                next = std::stoll(read_text(next_file));
            } catch (const std::exception&) {
                report.warnings.push_back(next_file.string() +
                                          ": unreadable; ids continue after the highest job");
            }
        }
        std::vector<fs::directory_entry> items(fs::directory_iterator(jobs_root()), {});
        std::sort(items.begin(), items.end(), [](const auto& a, const auto& b) {
            const auto ia = folder_id(a.path().filename().string());
            const auto ib = folder_id(b.path().filename().string());
            return ia && ib ? *ia < *ib : a.path() < b.path();
        });
        for (const auto& item : items) {
            const std::string name = item.path().filename().string();
            if (name.starts_with(incoming_prefix) || name.starts_with(removed_prefix)) {
                fs::remove_all(item.path());  // a submit or a remove cut short
                report.warnings.push_back("removed the leftover " + item.path().string());
                continue;
            }
            const auto id = folder_id(name);
            if (!item.is_directory() || !id) {
                report.warnings.push_back("ignored " + item.path().string() + ": not a job folder");
                continue;
            }
            next = std::max(next, *id + 1);
            const fs::path dir = item.path();
            for (const auto& f : fs::directory_iterator(dir))
                if (config::is_leftover_temp_file(f.path())) fs::remove(f.path());

            Entry e;
            e.record.id = *id;
            bool lost_now = false;  // it had printed, and its journal is gone
            try {
                const auto text = read_text(dir / "state.json");
                const auto j = nlohmann::json::parse(text, nullptr, false);
                if (j.is_discarded()) throw StateFileError("not valid JSON");
                e.record = record_from_json(j);
                if (e.record.id != *id)
                    throw StateFileError("id: " + std::to_string(e.record.id) +
                                         " does not match the folder");
                const fs::path journal = dir / "journal.jsonl";
                const JournalSummary js = read_journal(journal);
                if (js.torn_tail) {
                    repair_journal(journal);
                    report.warnings.push_back(journal.string() + ": cut a torn last record");
                }
                e.record.last_confirmed_event =
                    std::max(e.record.last_confirmed_event, js.last_confirmed);
                lost_now = !fs::exists(journal) && had_printed(e.record);
                if (fs::exists(journal)) e.journal = std::make_shared<JobJournal>(journal, js);
            } catch (const std::exception& ex) {
                e.record.state = JobState::failed;
                // A journal error names its file and line already.
                e.record.reason = dynamic_cast<const JournalError*>(&ex)
                                      ? std::string(ex.what())
                                      : (dir / "state.json").string() + ": " + ex.what();
                e.record.updated_at = config::utc_now();
                spdlog::error("job.load_failed job {}: {}", *id, e.record.reason);
                report.failed.push_back(*id);
                report.loaded.push_back(*id);
                jobs_.insert_or_assign(*id, std::move(e));
                continue;  // state.json stays as found, for whoever looks into it
            }
            JobRecord& r = e.record;
            const std::string lost = lost_now && !r.journal_lost ? lost_journal_text : "";
            if (lost_now) {
                r.journal_lost = true;
                report.warnings.push_back("job " + std::to_string(r.id) + lost_journal_text);
            }
            if (r.state == JobState::planning) {
                if (r.plan_attempts > options_.plan_retries) {
                    changed.push_back(change(e, JobState::failed,
                                             "planning was cut short by " +
                                                 std::to_string(r.plan_attempts) +
                                                 " restarts of the service; not retried again"));
                    report.failed.push_back(r.id);
                } else {
                    r.progress = {"queued", 0};
                    report.to_plan.push_back(r.id);
                }
            } else if (!allowed_targets(r.state, JobAction::service_restarted).empty()) {
                changed.push_back(change(
                    e, JobState::interrupted,
                    "the service restarted while the job was " + std::string(to_string(r.state)) +
                        "; last confirmed event " + std::to_string(r.last_confirmed_event) + lost));
                report.interrupted.push_back(r.id);
            } else if (!lost.empty()) {
                changed.push_back(change(e, r.state, r.reason + lost));  // the flag on the disk
            }
            report.loaded.push_back(r.id);
            jobs_.insert_or_assign(r.id, std::move(e));
        }
        for (auto* ids : {&report.loaded, &report.to_plan, &report.interrupted, &report.failed})
            std::sort(ids->begin(), ids->end());
        next_id_ = std::max(next_id_, next);
        prune_ended();
    }
    for (const auto& w : report.warnings) spdlog::warn("job.load {}", w);
    notify(changed);
    return report;
}

JobRecord JobStore::submit(const JobInput& input) {
    // Checked and written outside the lock, in a folder of its own: a bad job uses no id.
    const fs::path incoming = jobs_root() / (incoming_prefix + unique_suffix());
    auto read = std::make_shared<ReadJob>();
    try {
        write_job_input(incoming / "input", input);
        read->spec = check_job_input(incoming / "input", input);
        if (options_.settings_for) read->settings = options_.settings_for(read->spec);
    } catch (...) {
        std::error_code ec;
        fs::remove_all(incoming, ec);
        throw;
    }
    JobRecord r;
    {
        std::unique_lock lock(mu_);
        int waiting = 0;
        for (const auto& [id, e] : jobs_)
            waiting += e.record.state == JobState::planning || e.record.state == JobState::planned;
        if (waiting >= options_.max_queued) {
            lock.unlock();
            std::error_code ec;
            fs::remove_all(incoming, ec);
            throw JobConflict("the job queue is full (" + std::to_string(waiting) +
                              " jobs planning or planned, at most " +
                              std::to_string(options_.max_queued) +
                              "): start, abort or remove one first");
        }
        r.id = next_id_;
        config::write_file_durably(options_.state_dir / "next_id", std::to_string(r.id + 1) + "\n");
        ++next_id_;
        r.name = read->spec.name;
        r.state = JobState::planning;
        r.submitted_at = r.updated_at = config::utc_now();
        r.start_when_planned = input.start_when_planned;
        r.submitted_by = input.submitted_by;
        try {
            config::write_file_durably(incoming / "state.json", to_json(r).dump(2) + "\n");
            fs::create_directories(incoming / "plan");
            fs::rename(incoming, job_dir(r.id));
            config::sync_directory(jobs_root());
        } catch (...) {
            std::error_code ec;
            fs::remove_all(incoming, ec);  // its id stays unused
            throw;
        }
        planner::move_job_files(read->spec, fs::absolute(incoming / "input").string(),
                                fs::absolute(input_dir(r.id)).string());
        r.progress = {"queued", 0};
        jobs_.insert_or_assign(r.id, Entry{r, nullptr, std::move(read)});
        spdlog::info("job.submitted job {} '{}'", r.id, r.name);
    }
    notify({r});
    return r;
}

JobRecord JobStore::get(std::int64_t id) const {
    std::lock_guard lock(mu_);
    const Entry& e = entry(id);
    JobRecord r = e.record;
    if (e.journal) r.last_confirmed_event = e.journal->last_confirmed();
    return r;
}

std::vector<JobRecord> JobStore::list() const {
    std::lock_guard lock(mu_);
    std::vector<JobRecord> out;
    out.reserve(jobs_.size());
    for (const auto& [id, e] : jobs_) {
        out.push_back(e.record);
        if (e.journal) out.back().last_confirmed_event = e.journal->last_confirmed();
    }
    return out;
}

void JobStore::check_cell_free(std::int64_t id) const {
    for (const auto& [other, e] : jobs_) {
        if (other == id || !holds_cell(e.record.state)) continue;
        const JobState s = e.record.state;
        const bool on_bed = s == JobState::paused || s == JobState::interrupted;
        throw JobConflict("job " + std::to_string(other) + " is " + std::string(to_string(s)) +
                          (on_bed ? ": its part is on the bed: resume or abort it first"
                                  : ": one job prints at a time: wait until it ends or abort it"));
    }
}

JobRecord JobStore::request(std::int64_t id, JobAction action, const std::string& by) {
    if (!is_user_action(action))
        throw std::logic_error(std::string(to_string(action)) + " is not a user action");
    JobRecord result;
    {
        std::lock_guard lock(mu_);
        Entry& e = entry(id);
        const std::string refused = refusal(id, e.record.state, action);
        if (!refused.empty()) throw JobConflict(refused);
        if (action == JobAction::start || action == JobAction::resume) check_cell_free(id);
        if (action == JobAction::resume && e.record.journal_lost)
            throw JobConflict(
                "job " + std::to_string(id) + " cannot resume: its journal.jsonl is missing, so "
                "which events printed is known only up to event " +
                std::to_string(e.record.last_confirmed_event) +
                " (state.json, saved at every layer); the events after it may print again. "
                "Look at the part, then resume with --journal-lost (job.resume journal_lost: "
                "true) to go on after that event, or abort");
        if (action == JobAction::remove) {
            result = e.record;
            remove_folder(id);
            spdlog::info("job.removed job {}", id);
            return result;
        }
        if (action == JobAction::replan) {
            // A failed print keeps its history (journal, result): only a failed plan plans again.
            if (e.record.state == JobState::failed &&
                (e.journal || e.record.last_confirmed_event > 0 ||
                 fs::exists(job_dir(id) / "journal.jsonl")))
                throw JobConflict("job " + std::to_string(id) +
                                  " is failed: its print had started; submit it again to print "
                                  "another");
            e.record.reason.clear();
            e.record.plan_attempts = 0;
            e.record.start_when_planned = false;
            e.record.progress = {"queued", 0};
        }
        const JobState to = allowed_targets(e.record.state, action).front();
        // A start, or the re-entry of an interrupted print, is someone's: the record keeps whose.
        const std::string started_by = e.record.started_by;
        if (to == JobState::starting && !by.empty()) e.record.started_by = by;
        try {
            result = change(e, to, action == JobAction::abort ? "aborted by the operator" : "");
        } catch (...) {
            e.record.started_by = started_by;
            throw;
        }
        if (is_ended(to)) prune_ended();
    }
    notify({result});
    return result;
}

std::optional<JobRecord> JobStore::apply(std::int64_t id, JobAction event,
                                         const std::string& reason) {
    if (is_user_action(event))
        throw std::logic_error(std::string(to_string(event)) + " is a user action: use request()");
    JobRecord result;
    {
        std::lock_guard lock(mu_);
        Entry& e = entry(id);
        const auto targets = allowed_targets(e.record.state, event);
        if (targets.empty()) return std::nullopt;
        JobState to = targets.front();
        if (event == JobAction::start_refused) {
            // A resume that could not start stays interrupted; a fresh start goes back.
            const std::int64_t done = e.journal ? e.journal->last_confirmed() : 0;
            to = done > 0 || e.record.last_confirmed_event > 0 ? JobState::interrupted
                                                               : JobState::planned;
        }
        try {
            result = change(e, to, reason);
        } catch (const StateWriteError& x) {
            // The event happened (the cell faulted, the print ended) whether or not the disk
            // takes it: the service goes on with it in memory and says so. The disk keeps the
            // last state it took, which a restart reads back as interrupted.
            spdlog::critical("job.state_not_saved {}", x.what());
            const JobState from = e.record.state;  // change() put it back
            e.record.state = to;
            e.record.reason = (reason.empty() ? std::string(to_string(to)) : reason) +
                              "; not saved: " + x.what();
            stamp(e.record, from);
            result = e.record;
        }
        if (event == JobAction::plan_done || event == JobAction::plan_failed)
            e.record.progress = {};
        if (is_ended(to)) prune_ended();
    }
    notify({result});
    return result;
}

std::optional<PlanTicket> JobStore::begin_planning(std::int64_t id) {
    std::lock_guard lock(mu_);
    const auto it = jobs_.find(id);
    if (it == jobs_.end() || it->second.record.state != JobState::planning) return std::nullopt;
    JobRecord& r = it->second.record;
    ++r.plan_attempts;
    r.updated_at = config::utc_now();
    r.progress = {"read", 0};
    persist(r);  // before the work: a crash during it counts against plan_retries
    const fs::path plan = plan_dir(id);
    fs::remove_all(plan);
    fs::create_directories(plan);
    return PlanTicket{id, input_dir(id) / job_yaml_name, plan, std::move(it->second.read)};
}

void JobStore::planning_stopped(std::int64_t id) {
    std::lock_guard lock(mu_);
    const auto it = jobs_.find(id);
    if (it == jobs_.end() || it->second.record.state != JobState::planning) return;
    JobRecord& r = it->second.record;
    r.plan_attempts = std::max(0, r.plan_attempts - 1);
    r.progress = {"queued", 0};
    persist(r);
}

void JobStore::set_progress(std::int64_t id, const JobProgress& progress) {
    std::lock_guard lock(mu_);
    const auto it = jobs_.find(id);
    if (it != jobs_.end()) it->second.record.progress = progress;
}

std::shared_ptr<JobJournal> JobStore::journal(std::int64_t id) {
    std::lock_guard lock(mu_);
    Entry& e = entry(id);
    if (!e.journal) e.journal = std::make_shared<JobJournal>(job_dir(id) / "journal.jsonl");
    return e.journal;
}

void JobStore::confirm_progress(std::int64_t id, std::int64_t last_confirmed_event) {
    std::lock_guard lock(mu_);
    Entry& e = entry(id);
    if (last_confirmed_event <= e.record.last_confirmed_event) return;
    e.record.last_confirmed_event = last_confirmed_event;
    persist(e.record);
}

void JobStore::accept_lost_journal(std::int64_t id) {
    std::lock_guard lock(mu_);
    Entry& e = entry(id);
    if (!e.record.journal_lost) return;
    e.record.journal_lost = false;
    persist(e.record);
    spdlog::warn("job.journal_lost_accepted job {}: resumes after event {} (state.json) on the "
                 "operator's word",
                 id, e.record.last_confirmed_event);
}

void JobStore::remove_folder(std::int64_t id) {
    // Renamed away first: a crash during the removal leaves no half job behind.
    const fs::path gone = jobs_root() / (removed_prefix + std::to_string(id));
    fs::rename(job_dir(id), gone);
    config::sync_directory(jobs_root());
    std::error_code ec;
    fs::remove_all(gone, ec);
    jobs_.erase(id);
}

bool JobStore::remove_plan(std::int64_t id) {
    std::lock_guard lock(mu_);
    const auto it = jobs_.find(id);
    if (it == jobs_.end() || !is_ended(it->second.record.state)) return false;
    std::error_code ec;
    if (fs::remove_all(plan_dir(id), ec) == 0 || ec) return false;
    spdlog::info("job.plan_pruned job {}", id);
    return true;
}

void JobStore::prune_ended() {
    std::vector<std::int64_t> ended;
    for (const auto& [id, e] : jobs_)
        if (is_ended(e.record.state)) ended.push_back(id);
    const auto keep = static_cast<std::size_t>(options_.keep_completed);
    for (std::size_t i = 0; i + keep < ended.size(); ++i) {
        spdlog::info("job.pruned job {}", ended[i]);
        remove_folder(ended[i]);
    }
}

}  // namespace fibrecell::daemon::jobs
