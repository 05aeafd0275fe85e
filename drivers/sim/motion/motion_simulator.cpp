#include "drivers/sim/motion/motion_simulator.hpp"

#include "config/thread_priority.hpp"
#include "drivers/sim/motion/motion_plan.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace fibrecell::drivers::sim {

struct MotionSimulator::Impl {
    Impl(const SimClock& c, const MotionOptions& o) : clock(c), options(o), plan(c, o, c.now_s()) {}

    // A command acts on the robot as it is now, after the motion thread's last tick, its trigger
    // callbacks included (a callback's own command does not wait for itself); an idle plan is
    // first brought to the present.
    std::unique_lock<std::mutex> command() {
        std::unique_lock lock(mutex);
        if (std::this_thread::get_id() != thread.get_id())
            tick_done.wait(lock, [&] { return !firing; });
        plan.idle_until(clock.now_s());
        return lock;
    }
    std::uint64_t generation() const { return plan.changes() + controller_changes; }
    void notify() {
        wake.notify_one();
        changed.notify_all();
    }
    void run();
    // Where the robot goes next: to `until_s` (at least the next tick), but no further than the
    // tick of the first trigger due on the way.
    double catch_up_target(double tick_t, double until_s) const;

    const SimClock& clock;
    const MotionOptions options;
    mutable std::mutex mutex;
    std::condition_variable wake;             // the motion thread: something to move
    mutable std::condition_variable changed;  // wait(): the status changed
    std::condition_variable tick_done;        // commands: the trigger callbacks have run
    MotionPlan plan;
    bool firing = false;  // the motion thread runs a tick's trigger callbacks
    bool motors_on = true;
    std::string error;
    std::uint64_t controller_changes = 0;  // motors off / on, trigger failures
    bool quit = false;
    std::thread thread;  // last: starts once the rest is built
};

double MotionSimulator::Impl::catch_up_target(double tick_t, double until_s) const {
    double target = std::max(tick_t, until_s);
    if (const auto trigger = plan.next_trigger_s(); trigger && *trigger < target) {
        const double ticks = std::ceil((*trigger - plan.time()) / options.tick_s);
        target = std::max(tick_t, plan.time() + ticks * options.tick_s);
    }
    return target;
}

// Ticks of options.tick_s on the simulated clock while a motion is planned; parked otherwise.
void MotionSimulator::Impl::run() {
    std::unique_lock lock(mutex);
    while (!quit) {
        if (!plan.active()) {
            wake.wait(lock, [&] { return quit || plan.active(); });
            continue;
        }
        // Absolute tick times. A thread that fell behind the clock (a loaded machine, a high time
        // scale) catches up in one step instead of replaying every missed tick, but stops at the
        // first tick of a trigger due on the way: the trigger sees the robot where it fired. At a
        // high time scale it sleeps for several ticks at once (MotionOptions::min_wake_real_s).
        const double tick_t = plan.time() + options.tick_s;
        const double wake_t = catch_up_target(
            tick_t, clock.now_s() + options.min_wake_real_s * clock.time_scale());
        lock.unlock();
        clock.sleep_until(wake_t);
        lock.lock();
        auto due = plan.advance_to(catch_up_target(tick_t, clock.now_s()));
        std::string failure;
        if (!due.empty()) {
            // Outside the lock: a callback may ask where the robot is.
            firing = true;
            lock.unlock();
            for (auto& fire : due) {
                try {
                    fire();
                } catch (const std::exception& e) {
                    failure = e.what();
                }
            }
            lock.lock();
            firing = false;
            tick_done.notify_all();
        }
        const std::uint64_t before = generation();
        plan.settle();
        if (!failure.empty()) {
            // A trigger's equipment failed: a controller error, the robot held where it is.
            plan.halt();
            error = "trigger failed: " + failure;
            ++controller_changes;
        }
        if (generation() != before) changed.notify_all();
    }
}

MotionSimulator::MotionSimulator(const SimClock& clock, MotionOptions options)
    : impl_(std::make_unique<Impl>(clock, options)) {
    impl_->thread = std::thread([this] {
        config::make_thread_time_critical("sim.motion");
        impl_->run();
    });
}

MotionSimulator::~MotionSimulator() {
    {
        std::lock_guard lock(impl_->mutex);
        impl_->quit = true;
    }
    impl_->wake.notify_all();
    impl_->thread.join();
}

std::uint64_t MotionSimulator::queue(MotionSegment segment) {
    const auto lock = impl_->command();
    if (!impl_->motors_on)
        throw MotionError(segment.source + ": motors off (" + impl_->error + ")");
    const std::uint64_t id = impl_->plan.append(segment);
    impl_->notify();
    return id;
}

void MotionSimulator::stop_move() {
    const auto lock = impl_->command();
    impl_->plan.stop();
    impl_->notify();
}

void MotionSimulator::start_move() {
    const auto lock = impl_->command();
    impl_->plan.resume();
    impl_->notify();
}

void MotionSimulator::clear_path() {
    const auto lock = impl_->command();
    impl_->plan.clear();
    impl_->notify();
}

void MotionSimulator::motors_off(const std::string& why) {
    const auto lock = impl_->command();
    impl_->plan.halt();
    impl_->motors_on = false;
    impl_->error = why;
    ++impl_->controller_changes;
    impl_->notify();
}

void MotionSimulator::motors_on() {
    const auto lock = impl_->command();
    impl_->motors_on = true;
    impl_->error.clear();
    ++impl_->controller_changes;
    impl_->notify();
}

MotionStatus MotionSimulator::status() const {
    std::lock_guard lock(impl_->mutex);
    const MotionPlan& plan = impl_->plan;
    return {.moving = plan.active(),
            .stopped = plan.stopped(),
            .motors_on = impl_->motors_on,
            .pending = plan.pending(),
            .last_done = plan.last_done(),
            .error = impl_->error,
            .samples_dropped = plan.samples_dropped()};
}

bool MotionSimulator::done(std::uint64_t id) const {
    std::lock_guard lock(impl_->mutex);
    return impl_->plan.done(id);
}

bool MotionSimulator::in_position() const {
    std::lock_guard lock(impl_->mutex);
    return !impl_->plan.active() && impl_->plan.pending() == 0;
}

void MotionSimulator::wait(std::chrono::milliseconds timeout) const {
    std::unique_lock lock(impl_->mutex);
    const std::uint64_t seen = impl_->generation();
    impl_->changed.wait_for(lock, timeout, [&] { return impl_->generation() != seen; });
}

TrajectorySample MotionSimulator::current() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->plan.current();
}

rapid::Robtarget MotionSimulator::robtarget(const rapid::ToolData& tool,
                                            const rapid::WobjData& wobj) const {
    std::lock_guard lock(impl_->mutex);
    return impl_->plan.robtarget(tool, wobj);
}

std::vector<TrajectorySample> MotionSimulator::take_trajectory() {
    std::lock_guard lock(impl_->mutex);
    return impl_->plan.take_trajectory();
}

}  // namespace fibrecell::drivers::sim
