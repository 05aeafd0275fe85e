#include "daemon/api/latest_only_gate.hpp"

namespace fibrecell::api {

LatestOnlyGate::LatestOnlyGate(Strand strand, std::chrono::nanoseconds interval, Send send)
    : strand_(std::move(strand)), interval_(interval), send_(std::move(send)) {}

LatestOnlyGate::~LatestOnlyGate() {
    cancel();
}

LatestOnlyGate::Outcome LatestOnlyGate::offer(const std::string& topic, const std::string& method,
                                              Line line) {
    const std::string key = topic + '\n' + method;
    auto [it, fresh] = slots_.try_emplace(key);
    Slot& slot = it->second;
    const auto now = std::chrono::steady_clock::now();
    if (fresh) {
        slot.topic = topic;
        slot.timer = std::make_unique<boost::asio::steady_timer>(strand_);
    }
    if (!slot.held && (fresh || now - slot.last_sent >= interval_)) {
        slot.last_sent = now;
        send_(line);
        return Outcome::sent;
    }
    const Outcome outcome = slot.held ? Outcome::replaced : Outcome::held;
    slot.held = std::move(line);
    if (!slot.armed) {
        slot.armed = true;
        slot.generation = next_generation_++;
        slot.timer->expires_at(slot.last_sent + interval_);
        slot.timer->async_wait(
            [this, key, generation = slot.generation,
             alive = std::weak_ptr<char>(alive_)](const boost::system::error_code&) {
                if (alive.expired()) return;  // the gate (and its client) is gone
                on_timer(key, generation);
            });
    }
    return outcome;
}

void LatestOnlyGate::on_timer(const std::string& key, std::uint64_t generation) {
    const auto it = slots_.find(key);
    if (it == slots_.end() || !it->second.armed || it->second.generation != generation) return;
    Slot& slot = it->second;
    slot.armed = false;
    if (slot.held) send_held(slot);
}

void LatestOnlyGate::send_held(Slot& slot) {
    Line line = std::move(slot.held);
    slot.held.reset();
    slot.last_sent = std::chrono::steady_clock::now();
    if (slot.armed) {
        slot.timer->cancel();
        slot.armed = false;
    }
    send_(line);
}

void LatestOnlyGate::flush_topic(const std::string& topic) {
    for (auto& [key, slot] : slots_)
        if (slot.held && slot.topic == topic) send_held(slot);
}

void LatestOnlyGate::drop_unless(const std::function<bool(const std::string& topic)>& keep) {
    for (auto it = slots_.begin(); it != slots_.end();) {
        if (keep(it->second.topic)) {
            ++it;
        } else {
            it->second.timer->cancel();
            it = slots_.erase(it);
        }
    }
}

void LatestOnlyGate::set_interval(std::chrono::nanoseconds interval) {
    interval_ = interval;
}

void LatestOnlyGate::cancel() {
    for (auto& [key, slot] : slots_)
        if (slot.timer) slot.timer->cancel();
    slots_.clear();
}

}  // namespace fibrecell::api
