#include "daemon/printer/print_runner.hpp"

#include "config/durable_file.hpp"
#include "config/thread_priority.hpp"
#include "daemon/printer/print_figures.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>

namespace fibrecell::daemon::printer {

namespace abb = drivers::abb;
using Clock = std::chrono::steady_clock;
using devices::HotendTemps;
using jobs::JobAction;
using jobs::JobState;
using nlohmann::json;

namespace {

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// The head of the print after event `done`: that of the last head switch up to it.
std::optional<drivers::Head> head_at(const abb::PrintProgram& program, std::int64_t done) {
    for (auto i = std::min<std::int64_t>(done, static_cast<std::int64_t>(program.events.size()));
         i >= 1; --i) {
        const abb::ProgramEvent& e = program.events[static_cast<std::size_t>(i - 1)];
        if (e.kind == abb::EventKind::head_switch)
            return e.nozzle == abb::Nozzle::pla ? drivers::Head::pla : drivers::Head::ccf;
    }
    return std::nullopt;
}

}  // namespace

struct PrintRunner::Active {
    std::int64_t id = 0;
    print::PrintPlan plan;  // before the session, which keeps a reference to its program
    std::shared_ptr<jobs::JobJournal> journal;
    std::unique_ptr<print::PrintSession> session;
    Clock::time_point started = Clock::now();
    bool heaters_off = false;
    bool held = false;  // paused by the operator or on a fault (the runner's thread only)
    bool fault_reported = false;
    bool reselect_tool = false;  // the board restarted: its tool is the default one
    std::atomic<std::int64_t> last_confirmed{0};
    std::atomic<int> layer{-1};
    int layer_saved = -1;  // the layer of the last confirm_progress (the runner's thread only)
    jobs::JournalFed fed_saved;  // the last `fed` record written (the runner's thread only)
    // The job's filament: what earlier runs used, plus the link's ledger since this run began.
    jobs::JournalUsed used_before, used_saved;
    drivers::marlin::FeedTotals board_fed_at_start;
    std::uint64_t run = 0;  // Feed::run
    sync::SyncStatus sync;  // as of the last poll
};

PrintRunner::PrintRunner(jobs::JobStore& store, CellDevices& devices, const CellConfig& cell,
                         PrintRunnerOptions options)
    : store_(store), devices_(devices), cell_(cell), options_(options),
      heaters_(options.heaters, Clock::now()),
      last_run_(static_cast<std::uint64_t>(
          std::chrono::system_clock::now().time_since_epoch() / std::chrono::microseconds(1))) {
    thread_ = std::thread([this] {
        config::name_this_thread("print.runner");
        run();
    });
}

PrintRunner::~PrintRunner() { stop(); }

void PrintRunner::on_finished(std::function<void(std::int64_t)> f) { on_finished_ = std::move(f); }

void PrintRunner::on_feed(FeedObserver f) { on_feed_ = std::move(f); }

void PrintRunner::on_progress(std::function<void(std::int64_t, const json&)> f) {
    on_progress_ = std::move(f);
}

void PrintRunner::post(Command c) {
    {
        std::lock_guard lock(mu_);
        if (stopping_) {
            if (c.done) c.done("the service is stopping");
            return;
        }
        commands_.push_back(std::move(c));
    }
    cv_.notify_one();
}

void PrintRunner::start(std::int64_t id, Done done) { post({CommandKind::start, id, std::move(done)}); }
void PrintRunner::pause(std::int64_t id, Done done) { post({CommandKind::pause, id, std::move(done)}); }
void PrintRunner::resume(std::int64_t id, Done done) { post({CommandKind::resume, id, std::move(done)}); }
void PrintRunner::abort(std::int64_t id, Done done) { post({CommandKind::abort, id, std::move(done)}); }

void PrintRunner::abort_for_estop() {
    std::int64_t id = 0;
    {
        std::lock_guard lock(mu_);
        if (active_) id = active_->id;
    }
    if (id != 0) {
        try {
            store_.request(id, JobAction::abort);
        } catch (const std::exception& e) {
            spdlog::warn("print.estop job {}: {}", id, e.what());
        }
        abort(id, nullptr);
    }
}

std::optional<std::int64_t> PrintRunner::current_job() const {
    std::lock_guard lock(mu_);
    if (!active_) return std::nullopt;
    return active_->id;
}

json PrintRunner::print_status() const {
    std::lock_guard lock(mu_);
    if (!active_) return json::object();
    return {{"job", active_->id}, {"progress", progress_json()}, {"sync", live_sync_json(active_->sync)}};
}

json PrintRunner::heater_status() const {
    std::lock_guard lock(mu_);
    return heaters_.status(Clock::now());
}

json PrintRunner::progress_json() const {
    const Active& a = *active_;
    const auto total = static_cast<std::int64_t>(a.plan.program.events.size());
    const std::int64_t done = a.last_confirmed.load();
    const std::int64_t first = a.plan.first_event - 1;  // done before this run
    const double fraction = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
    const double elapsed = seconds(Clock::now() - a.started);
    json p = {{"layer", std::max(0, a.layer.load()) + 1},
              {"layers", a.plan.layers()},
              {"event", done},
              {"events", total},
              {"fraction", fraction},
              {"elapsed_s", elapsed},
              {"time_scale", devices_.time_scale()}};
    const double run_fraction =
        total > first ? static_cast<double>(done - first) / static_cast<double>(total - first) : 0;
    if (run_fraction > 0.02) p["eta_s"] = elapsed * (1 - run_fraction) / run_fraction;
    // Where the robot was at its last confirmed event (the bed frame), for the dashboard's layer
    // view: the service hears of events, not of every point between them.
    if (done >= 1 && done <= total) {
        const auto& e = a.plan.program.events[static_cast<std::size_t>(done - 1)];
        p["position_mm"] = {e.position_mm.x(), e.position_mm.y(), e.position_mm.z()};
        p["path"] = e.path + 1;
    }
    return p;
}

void PrintRunner::stop() {
    {
        std::lock_guard lock(mu_);
        if (stopping_ && !thread_.joinable()) return;
        stopping_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void PrintRunner::run() {
    std::unique_lock lock(mu_);
    while (!stopping_) {
        cv_.wait_for(lock, options_.poll_period, [&] { return stopping_ || !commands_.empty(); });
        while (!commands_.empty() && !stopping_) {
            Command c = std::move(commands_.front());
            commands_.pop_front();
            lock.unlock();
            handle(c);
            lock.lock();
        }
        if (stopping_) break;
        lock.unlock();
        try {
            poll_active();
        } catch (const std::exception& e) {
            // Nothing the print path throws may end the service: the engine holds the cell safe
            // on its own faults, and the job's state says what happened (JobStore::apply).
            spdlog::critical("print.poll_failed: {}", e.what());
        }
        tend_heaters();
        lock.lock();
    }
    // Leaving: the print is paused, not aborted, so that the job comes back interrupted.
    std::unique_ptr<Active> active = std::move(active_);
    for (Command& c : commands_)
        if (c.done) c.done("the service is stopping");
    commands_.clear();
    lock.unlock();
    if (active) {
        spdlog::warn("print.service_stopping job {}: robot paused, job left for resume", active->id);
        try {
            active->session->pause();
        } catch (const std::exception&) {
        }
        devices_.set_print(nullptr);
    }
    // Nobody is left to watch them; the resume after the restart heats them again.
    // Waited for (briefly): the process may end before the lines are written.
    if (auto off = send_heaters_off("the service is stopping"); off.valid())
        off.wait_for(std::chrono::seconds(2));
    if (active && active->journal) {
        // Answered in order: what the board took before the M104s is in the ledger now.
        save_used(*active);
        active->journal->flush();
    }
}

namespace {
PrintEvent event_of(PrintRunner::CommandKind kind) {
    switch (kind) {
        case PrintRunner::CommandKind::start: return PrintEvent::start;
        case PrintRunner::CommandKind::pause: return PrintEvent::pause;
        case PrintRunner::CommandKind::resume: return PrintEvent::resume;
        case PrintRunner::CommandKind::abort: return PrintEvent::abort;
    }
    return PrintEvent::abort;
}
}  // namespace

Situation PrintRunner::situation(PrintEvent event, std::int64_t id) {
    Situation s;
    {
        std::lock_guard lock(mu_);
        if (active_) {
            s.on_cell = active_->held ? OnCell::held : OnCell::printing;
            s.job_on_cell = active_->id;
            s.fault_reported = active_->fault_reported;
            s.heaters_off = active_->heaters_off;
            s.tool_lost = active_->reselect_tool;
        }
    }
    s.board_down = devices_.board().state() != drivers::DeviceState::active;
    if (event == PrintEvent::pause && s.job_on_cell != id) {
        try {
            s.job_ended = jobs::is_ended(store_.get(id).state);
        } catch (const jobs::JobNotFound&) {
        }
    }
    return s;
}

void PrintRunner::handle(Command& c) {
    std::string error;
    try {
        const PrintEvent event = event_of(c.kind);
        const Decision d = decide(event, c.id, situation(event, c.id));
        if (!d.refusal.empty()) {
            if (event == PrintEvent::start) {
                spdlog::error("print.start_refused job {}: {}", c.id, d.refusal);
                store_.apply(c.id, JobAction::start_refused, d.refusal);
            }
            throw std::runtime_error(d.refusal);
        }
        try {
            for (const Step step : d.steps) carry_out(step, c.id);
        } catch (const std::exception& e) {
            // A resume that could not bring the cell back leaves the job held with the reason.
            if (event == PrintEvent::resume) store_.apply(c.id, JobAction::faulted, e.what());
            throw;
        }
    } catch (const std::exception& e) {
        error = e.what();
        spdlog::error("print.command job {}: {}", c.id, error);
    }
    if (c.done) c.done(error);
}

// One step of the recovery table (recovery.hpp) for job `id`; `reason`: a fault's.
void PrintRunner::carry_out(Step step, std::int64_t id, const std::string& reason) {
    switch (step) {
        case Step::start_print: start_job(id); return;
        case Step::note_ended:
            // The print ended between the request and here: the job completed instead.
            spdlog::info("print.pause_too_late job {}: it had ended", id);
            return;
        case Step::pause_print: {
            active_->session->pause();
            // The robot brakes on the pause request: paused once it stands (or after 2 s).
            const auto deadline = Clock::now() + std::chrono::seconds(2);
            while (devices_.robot_io().snapshot().running && Clock::now() < deadline)
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
            {
                std::lock_guard heaters_lock(mu_);
                heaters_.paused(id, Clock::now());
            }
            active_->held = true;
            store_.apply(id, JobAction::pause_done);
            return;
        }
        case Step::reconnect_board: reconnect_board(*active_); return;
        case Step::reheat: {
            auto heat = devices_.board().submit(
                devices_.extruder().prepare(active_->plan.print.settings.hotends(), true));
            if (heat.wait_for(std::chrono::minutes(10)) != std::future_status::ready || !heat.get().ok())
                throw print::PrintError("resume: re-heating failed");
            active_->heaters_off = false;
            return;
        }
        case Step::reselect_tool: {
            // The board restarted on its default tool: the head of the print's last confirmed
            // event again, before the feed goes on.
            if (const auto head = head_at(active_->plan.program, active_->last_confirmed)) {
                auto select = devices_.board().submit(devices_.extruder().select(*head));
                if (select.wait_for(std::chrono::seconds(30)) != std::future_status::ready ||
                    !select.get().ok())
                    throw print::PrintError("resume: the tool select after the board's restart failed");
            }
            active_->reselect_tool = false;
            return;
        }
        case Step::resume_print:
            active_->session->resume();
            {
                std::lock_guard heaters_lock(mu_);
                heaters_.printing(id);
            }
            active_->fault_reported = false;
            active_->held = false;
            return;
        case Step::abort_print:
            active_->session->abort();
            finish("aborted by the operator", "aborted by the operator");
            return;
        case Step::hold: {
            Active& a = *active_;
            try {
                a.session->pause();
            } catch (const std::exception&) {
                // Not printing: already held by a fault of its own.
            }
            a.fault_reported = true;
            a.held = true;
            {
                std::lock_guard lock(mu_);
                heaters_.paused(a.id, Clock::now());
            }
            spdlog::error("print.fault job {}: {}", a.id, reason);
            store_.apply(a.id, JobAction::faulted, reason);
            return;
        }
        case Step::finish: {
            const auto shortfalls = active_->sync.stats.shortfalls;
            finish("completed");  // result.json first: a client that sees `completed` finds it
            if (shortfalls.empty())
                store_.apply(id, JobAction::print_done);
            else
                store_.apply(id, JobAction::print_short, shortfall_reason(shortfalls));
            return;
        }
    }
}

// A fault of the print on the cell (the session's, or its records'): held, as the table says.
void PrintRunner::fault(Active& a, const std::string& reason) {
    for (const Step step : decide(PrintEvent::fault, a.id, situation(PrintEvent::fault, a.id)).steps)
        carry_out(step, a.id, reason);
}

// The board fell out while the job was paused (a reset, a cable pulled and put back): open the
// link again. A board that restarted has lost its temperatures and its tool, so both are set
// again before the print goes on.
void PrintRunner::reconnect_board(Active& a) {
    spdlog::warn("print.board_reconnect job {}: the board link is {}; connecting again", a.id,
                 drivers::to_string(devices_.board().state()));
    try {
        devices_.connect(options_.connect_timeout);
    } catch (const std::exception& e) {
        throw print::PrintError(std::string("resume: the extruder board is still not connected: ") +
                                e.what());
    }
    devices_.extruder().forget_tool();
    a.heaters_off = true;  // re-heated (and waited for) before the resume
    a.reselect_tool = true;
    spdlog::info("print.board_reconnected job {}", a.id);
}

// The last fibre path was fed up to its cut when the print stopped: nothing is left to print,
// but the fibre still runs from the nozzle into the part. Cut it; the robot does not move.
void PrintRunner::cut_left_fibre(std::int64_t id) {
    try {
        devices_.connect(options_.connect_timeout);
        auto& x = devices_.extruder();
        std::vector<std::string> lines = x.select(drivers::Head::ccf);
        for (auto& l : x.cut()) lines.push_back(std::move(l));
        auto done = devices_.board().submit(lines);
        if (done.wait_for(std::chrono::seconds(30)) != std::future_status::ready)
            throw std::runtime_error("no answer from the extruder board within 30 s");
        const auto outcome = done.get();
        if (!outcome.ok()) throw std::runtime_error(outcome.detail);
        spdlog::info("print.fibre_cut job {}: the fibre left in the part was cut", id);
    } catch (const std::exception& e) {
        spdlog::warn("print.fibre_cut job {}: the fibre left in the part could not be cut ({}); "
                     "cut it by hand",
                     id, e.what());
    }
}

void PrintRunner::start_job(std::int64_t id) {
    auto refuse = [&](const std::string& why) {
        spdlog::error("print.start_refused job {}: {}", id, why);
        store_.apply(id, JobAction::start_refused, why);
        throw std::runtime_error(why);
    };
    const jobs::JobRecord record = store_.get(id);
    auto a = std::make_unique<Active>();
    a->id = id;
    const bool resuming = record.last_confirmed_event > 0;
    a->journal = store_.journal(id);
    a->used_before = a->used_saved = a->journal->last_used().value_or(jobs::JournalUsed{});
    a->board_fed_at_start = devices_.board().fed();
    a->run = ++last_run_;
    std::optional<print::FibreFed> fed;
    if (const auto f = a->journal->last_fed()) fed = print::FibreFed{f->sequence, f->mm};
    try {
        a->plan = print::load_print_plan(
            store_.plan_dir(id), cell_,
            resuming ? std::optional(record.last_confirmed_event) : std::nullopt, fed);
    } catch (const print::PlanRefused& e) {
        refuse(e.what());
    } catch (const std::exception& e) {
        refuse(std::string("cannot load the plan: ") + e.what());
    }
    if (a->plan.resume && a->plan.resume->nothing_left) {
        // Every path was done before the interruption: nothing moves, the job is complete.
        spdlog::info("print.nothing_left job {}: every path was done before the interruption", id);
        if (a->plan.resume->cut_first) cut_left_fibre(id);
        {
            std::lock_guard lock(mu_);
            active_ = std::move(a);
        }
        store_.apply(id, JobAction::print_started);
        finish("completed (nothing was left to print)");
        store_.apply(id, JobAction::print_done);
        return;
    }
    try {
        devices_.connect(options_.connect_timeout);
    } catch (const std::exception& e) {
        refuse(e.what());
    }
    a->last_confirmed = a->plan.first_event - 1;
    if (resuming) a->journal->resumed(a->plan.first_event);

    print::PrintOptions po;
    po.job_dir = cell_.rws.job_dir;
    // Real seconds (the simulated controller converts to its own time, docs/simcell.md).
    po.heartbeat_timeout_s = std::chrono::duration<double>(options_.heartbeat_timeout).count();
    po.signals = cell_.robot.signals.all();
    a->plan.print.settings.apply_to(po.sync);
    po.first_chunk = a->plan.first_chunk;
    po.chunk_count = a->plan.chunk_count;
    po.sync.time_scale = devices_.time_scale();
    po.sync.late_cut_mm = options_.late_cut_mm;
    po.sync.first_event = a->plan.first_event;
    po.sync.skip_events = a->plan.skip_events;
    if (const auto& r = a->plan.resume; r && !r->nothing_left) {
        po.resume_tool = r->nozzle == abb::Nozzle::pla ? drivers::Head::pla : drivers::Head::ccf;
        po.cut_before_start = r->cut_first;
        if (r->fibre_fed_mm > 0) {
            po.sync.resume_feed = sync::ResumeFeed{r->first_event, r->fibre_fed_mm, true};
            a->fed_saved = {r->first_event, r->fibre_fed_mm};
        }
        spdlog::info("print.reentry job {} at event {} (layer {}, path {}){}{}", id, r->first_event,
                     r->layer + 1, r->path + 1, r->cut_first ? ": the fibre in the part cut first" : "",
                     r->fibre_fed_mm > 0 ? fmt::format(", the rest laid from {:.1f} mm along it",
                                                       r->fibre_fed_mm)
                                         : std::string());
    }
    a->session = std::make_unique<print::PrintSession>(a->plan.program, a->plan.chunks,
                                                       devices_.links(), po);
    Active* raw = a.get();
    a->session->on_event_done([raw](const sync::EventDone& d) {
        // On the engine's thread, in order; queued, so the engine never waits for the disk.
        raw->journal->confirmed({d.sequence, d.kind, d.layer, d.path});
        raw->last_confirmed = d.sequence;
        if (d.layer >= 0) raw->layer = d.layer;
    });
    devices_.set_print(a->session.get());
    try {
        a->session->start();
    } catch (const std::exception& e) {
        devices_.set_print(nullptr);
        refuse(e.what());
    }
    spdlog::info("print.started job {} first_event={} events={} chunks={}", id, a->plan.first_event,
                 a->plan.program.events.size(), a->plan.chunks.size());
    {
        std::lock_guard lock(mu_);
        active_ = std::move(a);
        heaters_.printing(id);
    }
    store_.apply(id, JobAction::print_started);
}

void PrintRunner::poll_active() {
    std::unique_lock lock(mu_);
    if (!active_) return;
    Active& a = *active_;
    lock.unlock();
    const print::PrintStatus st = a.session->poll();
    // state.json follows at every layer, so a lost journal still says how far the print got.
    // Written here, not on the engine's thread: its fsyncs took the engine 0.5 s on a busy disk,
    // long enough for the robot to outrun the feed.
    if (const int layer = a.layer.load(); layer >= 0 && layer != a.layer_saved) {
        a.layer_saved = layer;
        try {
            store_.confirm_progress(a.id, a.last_confirmed.load());
        } catch (const std::exception& e) {
            // A full disk or an I/O error: the print may not go on unrecorded. The cell is made
            // safe as for a device fault (robot held, feed stopped); resume once it is mended.
            fault(a, std::string("the job's state cannot be saved: ") + e.what());
        }
    }
    save_fibre_fed(a, st.sync.metering);
    save_used(a);
    if (const auto failed = a.journal->take_failure())
        fault(a, "the job's journal cannot be written: " + *failed);
    lock.lock();
    a.sync = st.sync;
    const json progress = progress_json();
    lock.unlock();
    if (on_progress_) on_progress_(a.id, progress);

    switch (st.phase) {
        case print::PrintPhase::completed:
            for (const Step step :
                 decide(PrintEvent::completed, a.id, situation(PrintEvent::completed, a.id)).steps)
                carry_out(step, a.id);
            return;
        case print::PrintPhase::faulted: fault(a, st.reason); break;
        default: break;
    }
}

// The heater policy's timers, every poll: the M104 S0s when it says so. A paused job's heaters
// are heated again by its resume.
void PrintRunner::tend_heaters() {
    const HotendTemps t = devices_.temperatures();
    const bool heating = t.pla_target_c.value_or(0) > 0 || t.ccf_target_c.value_or(0) > 0;
    std::optional<std::string> reason;
    {
        std::lock_guard lock(mu_);
        heaters_.observe(heating, Clock::now());
        reason = heaters_.due(Clock::now());
    }
    if (!reason) return;
    reconnect_idle_board();
    if (!send_heaters_off(*reason).valid()) return;
    std::lock_guard lock(mu_);
    heaters_.switched_off(*reason, Clock::now());
    if (active_) active_->heaters_off = true;
}

// With no job on the cell, a board whose link fell out (a cable pulled and put back, a fault) is
// opened again for its heaters, every 10 s at most. A job's own board is the resume's to open.
void PrintRunner::reconnect_idle_board() {
    {
        std::lock_guard lock(mu_);
        if (active_) return;
    }
    if (devices_.board().state() == drivers::DeviceState::active) return;
    const auto now = Clock::now();
    if (last_idle_reconnect_ && now - *last_idle_reconnect_ < std::chrono::seconds(10)) return;
    last_idle_reconnect_ = now;
    try {
        devices_.connect(options_.connect_timeout);
        spdlog::info("print.board_reconnected for its heaters");
    } catch (const std::exception& e) {
        spdlog::warn("print.board_reconnect for its heaters failed: {}", e.what());
    }
}

// Both hotends to 0; no future (not valid()) when the board is not connected: its firmware's own
// thermal protection is then what remains (logged once until the board takes them).
std::future<drivers::marlin::CommandOutcome> PrintRunner::send_heaters_off(const std::string& reason) {
    if (devices_.board().state() != drivers::DeviceState::active) {
        if (!heaters_unreachable_logged_)
            spdlog::error("print.heaters_unreachable the heaters should go off ({}) but the "
                          "extruder board is {}; tried again until it answers",
                          reason, drivers::to_string(devices_.board().state()));
        heaters_unreachable_logged_ = true;
        return {};
    }
    const auto& x = devices_.extruder().config();
    auto sent = devices_.board().submit({"M104 T" + std::to_string(x.pla_tool) + " S0",
                                         "M104 T" + std::to_string(x.ccf_tool) + " S0"});
    heaters_unreachable_logged_ = false;
    spdlog::warn("print.heaters_off {}", reason);
    return sent;
}

// The journal follows a fibre path's feed, so that a re-entry after a crash lays only the rest
// of it (resume_point). Once per poll at most: what the board took since is fed twice then.
void PrintRunner::save_fibre_fed(Active& a, const sync::MeteringStatus& m) {
    if (m.sequence < 1 || m.sequence > static_cast<std::int64_t>(a.plan.program.events.size()))
        return;
    if (a.plan.program.events[static_cast<std::size_t>(m.sequence - 1)].kind !=
        abb::EventKind::fibre_start)
        return;
    // Lower than saved only after an MCU reset took back what the board had not run.
    if (m.sequence == a.fed_saved.sequence && m.e_fed_mm == a.fed_saved.mm) return;
    if (m.e_fed_mm <= 0) return;
    a.journal->fed({m.sequence, m.e_fed_mm});  // queued: a failed write shows in poll_active
    a.fed_saved = {m.sequence, m.e_fed_mm};
}

// The filament the job has taken so far, journaled when it changed (queued: the next poll sees a
// failed write). The board's count, never the plan's.
jobs::JournalUsed PrintRunner::save_used(Active& a) {
    const drivers::marlin::FeedTotals now = devices_.board().fed();
    const auto& x = cell_.extruder;
    const auto since = [&](int tool) { return now.of(tool) - a.board_fed_at_start.of(tool); };
    const jobs::JournalUsed used{a.used_before.pla_mm + since(x.pla_tool),
                                 a.used_before.fibre_mm + since(x.ccf_tool)};
    if (std::abs(used.pla_mm - a.used_saved.pla_mm) > 1e-6 ||
        std::abs(used.fibre_mm - a.used_saved.fibre_mm) > 1e-6) {
        a.journal->used(used);
        a.used_saved = used;
        if (on_feed_) on_feed_({a.id, a.run, used, a.layer.load()});
    }
    return used;
}

// The print ended (completed or aborted): its figures go to result.json beside state.json, and
// the heaters go off (now, or after the cell's hold).
void PrintRunner::finish(const std::string& outcome, const std::string& outcome_reason) {
    std::unique_ptr<Active> a;
    {
        std::lock_guard lock(mu_);
        a = std::move(active_);
        if (a) heaters_.ended(a->id, outcome, Clock::now());
    }
    if (!a) return;
    devices_.set_print(nullptr);
    const print::PrintStatus st = a->session ? a->session->poll() : print::PrintStatus{};
    const jobs::JournalUsed used = a->journal ? save_used(*a) : a->used_before;
    if (a->journal) a->journal->flush();  // the journal is whole before the job's end is saved
    const double elapsed = seconds(Clock::now() - a->started);
    json result = {{"elapsed_s", elapsed},
                   {"robot_time_s", elapsed * devices_.time_scale()},
                   {"time_scale", devices_.time_scale()},
                   {"events_done", a->last_confirmed.load()},
                   {"events", a->plan.program.events.size()},
                   {"first_event", a->plan.first_event}};
    if (!outcome_reason.empty()) result["reason"] = outcome_reason;
    result["used"] = {{"pla_mm", used.pla_mm}, {"fibre_mm", used.fibre_mm}};
    result.update(result_sync_json(st.sync));
    try {
        config::write_file_durably(store_.job_dir(a->id) / "result.json", result.dump(2) + "\n");
    } catch (const std::exception& e) {
        spdlog::error("print.result_lost job {}: {}", a->id, e.what());
    }
    spdlog::info("print.finished job {} {}", a->id, result.dump());
    a->session.reset();
    if (on_finished_) on_finished_(a->id);
}

}  // namespace fibrecell::daemon::printer
