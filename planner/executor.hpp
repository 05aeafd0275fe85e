#pragma once
// Independent tasks, run by whoever owns the threads: the planner starts none of its own. The
// service passes the one pool its planning workers share (daemon/jobs/thread_pool.hpp); tests and
// tools may pass a SerialExecutor.

#include <cstddef>
#include <functional>

namespace fibrecell::planner {

class Executor {
  public:
    virtual ~Executor() = default;
    // Runs task(0) .. task(count - 1), in any order, on any threads (the caller's included), and
    // returns when every task has returned. After a task throws, tasks not yet begun are skipped
    // and the first exception is rethrown once the running ones are done. May be called from
    // several threads at once and from inside a task.
    virtual void for_each(std::size_t count, const std::function<void(std::size_t)>& task) = 0;
};

// One task after another on the calling thread.
class SerialExecutor final : public Executor {
  public:
    void for_each(std::size_t count, const std::function<void(std::size_t)>& task) override {
        for (std::size_t i = 0; i < count; ++i) task(i);
    }
};

}  // namespace fibrecell::planner
