#include "drivers/sim/rapid_exec/interrupts.hpp"

#include "drivers/abb/rapid/names.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::drivers::sim::rapid_exec {

namespace {
// The controller's interrupt queue is bounded; a flood of raises (a fast signal while a TRAP
// runs) must not grow without end.
constexpr std::size_t max_pending = 64;
}  // namespace

std::int64_t interrupt_number(const rapid::Value& v) {
    if (!v.is_num() || !(std::fabs(v.num()) < 1e15) || v.num() != std::trunc(v.num())) return 0;
    return static_cast<std::int64_t>(v.num());
}

std::int64_t InterruptTable::connect(std::shared_ptr<LoadedModule> module,
                                     const rapid::Routine& trap) {
    const std::int64_t n = next_number_++;
    table_[n] = Interrupt{.module = std::move(module), .trap = &trap};
    return n;
}

Interrupt* InterruptTable::find(std::int64_t number) {
    auto it = table_.find(number);
    return it == table_.end() ? nullptr : &it->second;
}

void InterruptTable::remove(std::int64_t number) {
    table_.erase(number);
    pending_.erase(std::remove(pending_.begin(), pending_.end(), number), pending_.end());
}

void InterruptTable::clear() {
    table_.clear();
    pending_.clear();
    enabled_ = true;
}

void InterruptTable::raise(std::int64_t number, Interrupt& i) {
    if (i.asleep || pending_.size() >= max_pending) return;
    pending_.push_back(number);
    if (i.single) i.source = Interrupt::Source::none;
}

void InterruptTable::signal_changed(const std::string& signal, double value) {
    for (auto& [n, i] : table_) {
        if (!rapid::same_name(i.signal, signal)) continue;
        if (i.source == Interrupt::Source::signal_gi ||
            (i.source == Interrupt::Source::signal_di && value == i.edge))
            raise(n, i);
    }
}

double InterruptTable::timers_due(double now_s) {
    double next = std::numeric_limits<double>::infinity();
    for (auto& [n, i] : table_) {
        if (i.source != Interrupt::Source::timer) continue;
        if (i.due_s <= now_s) {
            raise(n, i);
            // A late wake-up raises once, not once per missed period.
            i.due_s = std::max(i.due_s + i.period_s, now_s);
            if (i.due_s <= now_s) i.due_s = now_s + i.period_s;
        }
        if (i.source == Interrupt::Source::timer) next = std::min(next, i.due_s);
    }
    return next;
}

std::optional<std::int64_t> InterruptTable::next_pending() {
    if (!enabled_ || pending_.empty()) return std::nullopt;
    const std::int64_t n = pending_.front();
    pending_.pop_front();
    if (find(n) == nullptr) return std::nullopt;
    return n;
}

}  // namespace fibrecell::drivers::sim::rapid_exec
