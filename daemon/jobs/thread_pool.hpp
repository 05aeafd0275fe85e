#pragma once
// The service's one pool of planning threads (planner::Executor): every planning worker's layers
// run on it, so two jobs planned at once share the cores instead of each starting a pool of its
// own. A caller of for_each() works on its own tasks too while it waits, so a task may call
// for_each() again without a deadlock.
//
//   ThreadPool pool({.threads = 0, .nice = 10});   // one thread per core, below the print's
//   run_layer_stage(job, field, {.executor = &pool});

#include "planner/executor.hpp"

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace fibrecell::daemon::jobs {

struct ThreadPoolOptions {
    int threads = 0;  // 0: one per core (the callers of for_each() work besides)
    // Nice value of the pool's threads: planning takes every core it gets, and a print's sync
    // threads must still run within milliseconds. Never raises the priority.
    int nice = 0;
};

class ThreadPool final : public planner::Executor {
  public:
    explicit ThreadPool(ThreadPoolOptions options = {});
    ~ThreadPool() override;  // joins the threads; no for_each() may be running
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    void for_each(std::size_t count, const std::function<void(std::size_t)>& task) override;

    std::size_t threads() const { return threads_.size(); }

  private:
    struct Batch;
    void work();
    // Runs one unclaimed task of `b`; false when none is left to claim.
    static bool run_one(Batch& b);

    std::mutex mu_;
    std::condition_variable wake_;
    std::deque<std::shared_ptr<Batch>> batches_;  // with unclaimed tasks
    bool stopping_ = false;
    std::vector<std::thread> threads_;
};

}  // namespace fibrecell::daemon::jobs
