#include "daemon/jobs/thread_pool.hpp"

#include "config/thread_priority.hpp"

#include <algorithm>
#include <atomic>
#include <exception>

namespace fibrecell::daemon::jobs {

// One for_each() call: its tasks are claimed by index, by the pool's threads and by the caller.
struct ThreadPool::Batch {
    const std::function<void(std::size_t)>* task = nullptr;
    std::size_t count = 0;
    std::atomic<std::size_t> next{0};  // next index to claim
    std::atomic<bool> failed{false};   // skip what is not begun
    std::mutex mu;
    std::condition_variable done_cv;
    std::size_t done = 0;  // claimed tasks that returned (or were skipped)
    std::exception_ptr failure;
};

ThreadPool::ThreadPool(ThreadPoolOptions options) {
    const int n = options.threads > 0
                      ? options.threads
                      : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    for (int i = 0; i < n; ++i)
        threads_.emplace_back([this, nice = options.nice] {
            config::name_this_thread("jobs.pool");
            config::lower_thread_priority(nice);
            work();
        });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mu_);
        stopping_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
}

bool ThreadPool::run_one(Batch& b) {
    const std::size_t i = b.next.fetch_add(1);
    if (i >= b.count) return false;
    if (!b.failed.load()) {
        try {
            (*b.task)(i);
        } catch (...) {
            std::lock_guard lock(b.mu);
            if (!b.failure) b.failure = std::current_exception();
            b.failed = true;
        }
    }
    std::lock_guard lock(b.mu);
    if (++b.done == b.count) b.done_cv.notify_all();
    return true;
}

void ThreadPool::work() {
    std::unique_lock lock(mu_);
    for (;;) {
        wake_.wait(lock, [&] { return stopping_ || !batches_.empty(); });
        if (stopping_) return;
        std::shared_ptr<Batch> b = batches_.front();
        lock.unlock();
        const bool ran = run_one(*b);
        lock.lock();
        // Every task claimed: the batch leaves the queue (its caller waits for the running ones).
        if (!ran && !batches_.empty() && batches_.front() == b) batches_.pop_front();
    }
}

void ThreadPool::for_each(std::size_t count, const std::function<void(std::size_t)>& task) {
    if (count == 0) return;
    auto b = std::make_shared<Batch>();
    b->task = &task;
    b->count = count;
    if (count > 1) {
        {
            std::lock_guard lock(mu_);
            batches_.push_back(b);
        }
        wake_.notify_all();
    }
    while (run_one(*b)) {
    }
    {
        std::lock_guard lock(mu_);
        std::erase(batches_, b);
    }
    std::unique_lock lock(b->mu);
    b->done_cv.wait(lock, [&] { return b->done == b->count; });
    if (b->failure) std::rethrow_exception(b->failure);
}

}  // namespace fibrecell::daemon::jobs
