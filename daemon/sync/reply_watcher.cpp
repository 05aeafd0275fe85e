#include "daemon/sync/reply_watcher.hpp"

#include "config/thread_priority.hpp"

namespace fibrecell::daemon::sync {
namespace {

// How often a wait on a reply looks up to see whether the watcher is stopping.
constexpr auto stop_check = std::chrono::milliseconds(20);

}  // namespace

ReplyWatcher::ReplyWatcher(Sink sink) : sink_(std::move(sink)), thread_([this] {
          config::make_thread_time_critical("sync.replies");
          run();
      }) {}

ReplyWatcher::~ReplyWatcher() {
    {
        std::lock_guard lock(mu_);
        stopping_ = true;
    }
    cv_.notify_all();
    thread_.join();
}

void ReplyWatcher::watch(std::uint64_t ticket, std::future<drivers::marlin::CommandOutcome> reply) {
    {
        std::lock_guard lock(mu_);
        pending_.push_back({ticket, std::move(reply)});
    }
    cv_.notify_all();
}

void ReplyWatcher::run() {
    std::unique_lock lock(mu_);
    while (true) {
        cv_.wait(lock, [&] { return stopping_ || !pending_.empty(); });
        if (stopping_) return;
        Pending& oldest = pending_.front();
        lock.unlock();
        // wait_for returns the moment the reply is ready; the period only bounds a stop.
        const bool ready = oldest.reply.wait_for(stop_check) == std::future_status::ready;
        const auto at = std::chrono::steady_clock::now();
        lock.lock();
        if (!ready) continue;
        Pending done = std::move(pending_.front());
        pending_.pop_front();
        lock.unlock();
        sink_(done.ticket, done.reply.get(), at);
        lock.lock();
    }
}

}  // namespace fibrecell::daemon::sync
