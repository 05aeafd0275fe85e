// The public face of the simulated RAPID task: loading by the controller, program pointer,
// start/stop (never blocking: the task thread parks at its next statement boundary), input
// changes, data access and status.
#include "drivers/sim/rapid_exec/task_impl.hpp"

#include "config/thread_priority.hpp"
#include "drivers/abb/rapid/names.hpp"

#include <algorithm>
#include <stdexcept>

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;

namespace {

// A lock on the program state taken from outside the task thread: tells the thread to let go
// at its next statement boundary.
class DataLock {
  public:
    DataLock(std::mutex& state_mu, std::atomic<int>& waiters) {
        ++waiters;
        lock_ = std::unique_lock(state_mu);
        --waiters;
    }

  private:
    std::unique_lock<std::mutex> lock_;
};

bool running(std::mutex& inbox_mu, const bool& want_run) {
    const std::lock_guard g(inbox_mu);
    return want_run;
}

// Bounded, like the controller's event queue: a stopped task must not collect heartbeats forever.
constexpr std::size_t max_signal_events = 1024;

}  // namespace

RapidTask::RapidTask(const SimClock& clock, MotionSimulator& motion, TaskIo io)
    : impl_(std::make_unique<Impl>(clock, motion, std::move(io))) {}

RapidTask::~RapidTask() {
    {
        const std::lock_guard g(impl_->inbox_mu);
        impl_->quit = true;
        ++impl_->inbox_seq;
    }
    impl_->inbox_cv.notify_all();
    {
        const std::lock_guard g(impl_->thread_mu);
        if (impl_->thread.joinable()) impl_->thread.join();
    }
    const std::lock_guard g(impl_->trigger_gate->mu);
    impl_->trigger_gate->open = false;
}

void RapidTask::load(rapid::Module module) {
    const DataLock data(impl_->state_mu, impl_->data_waiters);
    if (running(impl_->inbox_mu, impl_->want_run)) throw std::logic_error("load: stop the task first");
    auto loaded = rapid_exec::instantiate(std::make_shared<const rapid::Module>(std::move(module)),
                                          false, "");
    auto& ms = impl_->modules;
    auto it = std::find_if(ms.begin(), ms.end(), [&](const auto& m) {
        return rapid::same_name(m->name(), loaded->name());
    });
    if (it != ms.end())
        *it = std::move(loaded);
    else
        ms.push_back(std::move(loaded));
    impl_->publish_loaded();
}

void RapidTask::unload(const std::string& module_name) {
    const DataLock data(impl_->state_mu, impl_->data_waiters);
    if (running(impl_->inbox_mu, impl_->want_run)) throw std::logic_error("unload: stop the task first");
    auto& ms = impl_->modules;
    auto it = std::find_if(ms.begin(), ms.end(),
                           [&](const auto& m) { return rapid::same_name(m->name(), module_name); });
    if (it == ms.end()) throw std::out_of_range("unload: no module " + module_name);
    ms.erase(it);
    impl_->publish_loaded();
}

void RapidTask::reset_pp() {
    {
        const DataLock data(impl_->state_mu, impl_->data_waiters);
        if (running(impl_->inbox_mu, impl_->want_run)) throw std::logic_error("reset_pp: stop the task first");
        auto& ms = impl_->modules;
        ms.erase(std::remove_if(ms.begin(), ms.end(), [](const auto& m) { return m->dynamic; }),
                 ms.end());
        for (auto& m : ms)
            for (auto& [key, v] : m->data)
                if (v.storage != rapid::Storage::pers) v.value = v.initial;
        impl_->interrupts.clear();
        impl_->loads.clear();
        impl_->restart_pending = true;  // a thread stopped inside the program starts over
        impl_->publish_loaded();
        const std::lock_guard g(impl_->status_mu);
        impl_->shown.module.clear();
        impl_->shown.line = 0;
        if (impl_->shown.state == TaskState::error) impl_->shown.state = TaskState::stopped;
    }
    // PP to main drops the path the program queued and its StopMove.
    impl_->motion.clear_path();
    if (impl_->program_stopmove.exchange(false) && !impl_->task_stopmove)
        impl_->motion.start_move();
}

void RapidTask::start() {
    {
        const DataLock data(impl_->state_mu, impl_->data_waiters);
        const bool has_main = std::any_of(
            impl_->modules.begin(), impl_->modules.end(), [](const auto& m) {
                const rapid::Routine* r = m->module->find_routine("main");
                return r != nullptr && !r->local && r->kind == rapid::RoutineKind::proc;
            });
        if (!has_main) throw std::logic_error("start: no main routine in the task");
    }
    // Running from now until it stops, ends or fails: shown before the thread may end or fail.
    impl_->set_state(TaskState::running);
    {
        const std::lock_guard g(impl_->inbox_mu);
        impl_->want_run = true;
        ++impl_->inbox_seq;
    }
    impl_->inbox_cv.notify_all();
    if (impl_->task_stopmove.exchange(false) && !impl_->program_stopmove)
        impl_->motion.start_move();
    const std::lock_guard g(impl_->thread_mu);
    if (!impl_->thread.joinable()) impl_->thread = std::thread([this] {
            config::make_thread_time_critical("sim.rapid_task");
            impl_->thread_main();
        });
}

void RapidTask::stop() {
    bool was_running = false, thread_active = false;
    {
        const std::lock_guard g(impl_->inbox_mu);
        was_running = impl_->want_run;
        thread_active = impl_->thread_active;
        impl_->want_run = false;
        ++impl_->inbox_seq;
    }
    impl_->inbox_cv.notify_all();
    if (!thread_active) {  // stopped before the thread took the start: it will not report it
        const std::lock_guard g(impl_->status_mu);
        if (impl_->shown.state == TaskState::running) impl_->shown.state = TaskState::stopped;
    }
    if (was_running) {
        impl_->motion.stop_move();
        impl_->task_stopmove = true;
    }
}

void RapidTask::signal_changed(const std::string& signal, double value) {
    {
        const std::lock_guard g(impl_->inbox_mu);
        auto& events = impl_->signal_events;
        if (events.size() >= max_signal_events) events.pop_front();
        events.emplace_back(signal, value);
        ++impl_->inbox_seq;
    }
    impl_->inbox_cv.notify_all();
}

namespace {

rapid_exec::Variable& find_data(std::vector<std::shared_ptr<rapid_exec::LoadedModule>>& modules,
                                const std::string& module, const std::string& name) {
    for (auto& m : modules) {
        if (!rapid::same_name(m->name(), module)) continue;
        auto it = m->data.find(rapid::fold(name));
        if (it == m->data.end())
            throw std::out_of_range("no data " + name + " in module " + module);
        return it->second;
    }
    throw std::out_of_range("no module " + module + " in the task");
}

}  // namespace

rapid::Value RapidTask::read_data(const std::string& module, const std::string& name) const {
    const DataLock data(impl_->state_mu, impl_->data_waiters);
    return find_data(impl_->modules, module, name).value;
}

void RapidTask::write_data(const std::string& module, const std::string& name,
                           const rapid::Value& value) {
    {
        const DataLock data(impl_->state_mu, impl_->data_waiters);
        rapid_exec::Variable& v = find_data(impl_->modules, module, name);
        if (v.storage == rapid::Storage::constant)
            throw std::invalid_argument(module + "." + name + " is a CONST");
        std::string why;
        auto fitted = rapid::conform_array(value, v.type, v.extents, &why);
        if (!fitted)
            throw std::invalid_argument(module + "." + name + " (" + v.type + "): " + why);
        v.value = std::move(*fitted);
    }
    impl_->bump_inbox();  // a waiting instruction looks at its condition again
}

TaskStatus RapidTask::status() const {
    const std::lock_guard g(impl_->status_mu);
    return impl_->shown;
}

}  // namespace fibrecell::drivers::sim
