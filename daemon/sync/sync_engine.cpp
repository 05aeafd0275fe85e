#include "daemon/sync/sync_engine.hpp"

#include "config/thread_priority.hpp"
#include "daemon/sync/event_processor.hpp"
#include "daemon/sync/reply_watcher.hpp"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <variant>

namespace fibrecell::daemon::sync {

using drivers::marlin::CommandOutcome;

namespace {

struct BoardReply {
    std::uint64_t ticket;
    CommandOutcome outcome;
    SteadyClock::time_point at;
};
struct PauseRequest {};
struct ResumeRequest {};

using Input = std::variant<drivers::abb::EventCounterChange, drivers::abb::RobotIoStateChange,
                           drivers::marlin::TemperatureReport, BoardReply, PauseRequest,
                           ResumeRequest>;

}  // namespace

struct SyncEngine::Impl {
    Impl(const drivers::abb::PrintProgram& program, drivers::ExtruderController& extruder,
         drivers::marlin::MarlinLink& board, drivers::abb::RobotIoLink& robot, SyncOptions options)
        : timings(options.timings ? options.timings
                                  : std::make_shared<EventTimings>(options.timing_window)),
          processor({program, extruder, board, robot}, options, observers,
                    [this](std::uint64_t ticket, std::future<CommandOutcome> reply) {
                        watcher.watch(ticket, std::move(reply));
                    },
                    *timings),
          watcher([this](std::uint64_t ticket, const CommandOutcome& outcome,
                         SteadyClock::time_point at) { post(BoardReply{ticket, outcome, at}); }) {}

    void post(Input in) {
        {
            std::lock_guard lock(mu);
            inbox.push_back(std::move(in));
        }
        cv.notify_one();
    }

    void handle(Input& in) {
        const auto now = SteadyClock::now();
        std::visit(
            [&](auto& v) {
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, drivers::abb::EventCounterChange>)
                    processor.counter_changed(v);
                else if constexpr (std::is_same_v<T, drivers::abb::RobotIoStateChange>)
                    processor.robot_link_state(v);
                else if constexpr (std::is_same_v<T, drivers::marlin::TemperatureReport>)
                    processor.temperature(v);
                else if constexpr (std::is_same_v<T, BoardReply>)
                    processor.board_reply(v.ticket, v.outcome, v.at);
                else if constexpr (std::is_same_v<T, PauseRequest>)
                    processor.pause(now);
                else
                    processor.resume(now);
            },
            in);
    }

    // Runs `step` on the processor; the engine never throws from its thread.
    template <class Step>
    void guarded(Step step) {
        try {
            step();
        } catch (const std::exception& e) {
            processor.fault(std::string("sync engine: ") + e.what());
        }
    }

    void publish() {
        SyncStatus s = processor.status();
        std::lock_guard lock(mu);
        s.running = true;
        published = std::move(s);
    }

    void run() {
        guarded([&] { processor.begin(); });
        publish();
        std::unique_lock lock(mu);
        while (true) {
            const auto wake = processor.next_wakeup();
            const auto ready = [&] { return stopping || !inbox.empty(); };
            if (wake)
                cv.wait_until(lock, *wake, ready);
            else
                cv.wait(lock, ready);
            if (stopping) return;
            std::deque<Input> batch;
            batch.swap(inbox);
            lock.unlock();
            for (Input& in : batch) guarded([&] { handle(in); });
            guarded([&] { processor.meter(SteadyClock::now()); });
            publish();
            lock.lock();
        }
    }

    // Declared first: the watcher's thread posts into them until it is joined.
    mutable std::mutex mu;
    std::condition_variable cv;
    std::deque<Input> inbox;
    bool stopping = false;
    SyncStatus published;

    SyncObservers observers;
    std::shared_ptr<EventTimings> timings;
    EventProcessor processor;  // only the worker thread touches it once started
    ReplyWatcher watcher;
    bool started = false;
    std::thread worker;
};

SyncEngine::SyncEngine(const drivers::abb::PrintProgram& program,
                       drivers::ExtruderController& extruder, drivers::marlin::MarlinLink& board,
                       drivers::abb::RobotIoLink& robot, SyncOptions options) {
    validate(options, static_cast<std::int64_t>(program.events.size()));
    impl_ = std::make_unique<Impl>(program, extruder, board, robot, options);
    impl_->published = impl_->processor.status();
}

SyncEngine::~SyncEngine() { stop(); }

void SyncEngine::on_event_done(std::function<void(const EventDone&)> f) {
    impl_->observers.event_done = std::move(f);
}
void SyncEngine::on_fault(std::function<void(const std::string&)> f) {
    impl_->observers.fault = std::move(f);
}
void SyncEngine::on_progress(std::function<void(const SyncProgress&)> f) {
    impl_->observers.progress = std::move(f);
}

void SyncEngine::start() {
    if (impl_->started) return;  // once: a second begin() would prepare the board again
    impl_->started = true;
    impl_->worker = std::thread([this] {
        config::make_thread_time_critical("sync.engine");
        impl_->run();
    });
}

void SyncEngine::stop() {
    if (!impl_->worker.joinable()) return;
    {
        std::lock_guard lock(impl_->mu);
        impl_->stopping = true;
    }
    impl_->cv.notify_one();
    impl_->worker.join();
    std::lock_guard lock(impl_->mu);
    impl_->published.running = false;
}

void SyncEngine::robot_event(const drivers::abb::EventCounterChange& change) {
    impl_->post(change);
}
void SyncEngine::robot_link_state(const drivers::abb::RobotIoStateChange& change) {
    impl_->post(change);
}
void SyncEngine::board_temperature(const drivers::marlin::TemperatureReport& report) {
    impl_->post(report);
}
void SyncEngine::pause() { impl_->post(PauseRequest{}); }
void SyncEngine::resume() { impl_->post(ResumeRequest{}); }

SyncStatus SyncEngine::status() const {
    SyncStatus s;
    {
        std::lock_guard lock(impl_->mu);
        s = impl_->published;
    }
    s.stats.timing = impl_->timings->summary();
    return s;
}

}  // namespace fibrecell::daemon::sync
