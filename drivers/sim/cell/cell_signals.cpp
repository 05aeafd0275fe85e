#include "drivers/sim/cell/cell_signals.hpp"

#include "drivers/abb/rapid/names.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace fibrecell::drivers::sim {

namespace {

bool is_group(int bits) {
    return bits > 1;
}

// A value written to an output of `bits` bits: a whole number that fits.
std::uint16_t checked_output(const std::string& signal, double value, int bits) {
    const double max = is_group(bits) ? 65535 : 1;
    if (!(value >= 0 && value <= max) || value != std::trunc(value))
        throw std::invalid_argument("value " + std::to_string(value) + " does not fit the " +
                                    std::to_string(bits) + "-bit output " + signal);
    return static_cast<std::uint16_t>(value);
}

}  // namespace

CellSignals::CellSignals(abb::RobotSignals names, std::chrono::milliseconds heartbeat_filter)
    : names_(std::move(names)), heartbeat_filter_(heartbeat_filter) {
    const std::pair<const std::string*, Id> all[] = {
        {&names_.release, Id::release}, {&names_.pause, Id::pause},
        {&names_.abort, Id::abort},     {&names_.heartbeat_in, Id::heartbeat_in},
        {&names_.event, Id::event},     {&names_.barrier, Id::barrier},
        {&names_.running, Id::running}, {&names_.heartbeat_out, Id::heartbeat_out},
    };
    for (const auto& [name, id] : all) {
        if (!ids_.emplace(abb::rapid::fold(*name), id).second)
            throw std::invalid_argument("signal name " + *name + " is used twice");
        values_[id] = 0;
    }
}

void CellSignals::attach(RobotIoServer& coupler) {
    std::lock_guard lock(values_mu_);
    coupler_ = &coupler;
    const ServiceCommands c = coupler.commands();
    values_[Id::release] = c.release;
    values_[Id::pause] = c.pause ? 1 : 0;
    values_[Id::abort] = c.abort ? 1 : 0;
    values_[Id::heartbeat_in] = c.heartbeat ? 1 : 0;
}

void CellSignals::on_input(std::function<void(const std::string&, double)> f) {
    std::lock_guard lock(forward_mu_);
    on_input_ = std::move(f);
}

void CellSignals::detach() {
    {
        std::lock_guard lock(forward_mu_);
        on_input_ = nullptr;
    }
    std::lock_guard lock(values_mu_);
    coupler_ = nullptr;
}

CellSignals::Id CellSignals::find(const std::string& signal) const {
    const auto it = ids_.find(abb::rapid::fold(signal));
    if (it == ids_.end())
        throw std::out_of_range("no signal named " + signal + " in the I/O configuration");
    return it->second;
}

void CellSignals::set_input(Id id, double value,
                            std::vector<std::pair<std::string, double>>& changes) {
    double& v = values_[id];
    if (v == value) return;
    v = value;
    const std::string& name = id == Id::release ? names_.release
                              : id == Id::pause ? names_.pause
                              : id == Id::abort ? names_.abort
                                                : names_.heartbeat_in;
    changes.emplace_back(name, value);
}

void CellSignals::commands_changed(const ServiceCommands& c) {
    std::lock_guard forward(forward_mu_);
    std::vector<std::pair<std::string, double>> changes;
    {
        std::lock_guard lock(values_mu_);
        if (coupler_ == nullptr) return;
        // Pause and abort before the release: a release written together with an abort must not
        // let a barrier pass first.
        set_input(Id::abort, c.abort ? 1 : 0, changes);
        set_input(Id::pause, c.pause ? 1 : 0, changes);
        set_input(Id::release, c.release, changes);
        set_input(Id::heartbeat_in, c.heartbeat ? 1 : 0, changes);
    }
    if (!on_input_) return;
    for (const auto& [name, value] : changes) on_input_(name, value);
}

double CellSignals::read(const std::string& signal) const {
    const Id id = find(signal);
    std::lock_guard lock(values_mu_);
    return values_.at(id);
}

void CellSignals::write(const std::string& signal, double value) {
    const Id id = find(signal);
    if (id == Id::release || id == Id::pause || id == Id::abort || id == Id::heartbeat_in)
        throw std::invalid_argument(signal + " is an input and cannot be set");
    const int bits = id == Id::event || id == Id::barrier ? 16 : 1;
    const std::uint16_t v = checked_output(signal, value, bits);
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(values_mu_);
    const bool changed = values_[id] != v;
    values_[id] = v;
    if (id != Id::heartbeat_out) {
        history_.push_back({signal, static_cast<double>(v), now});
        if (history_.size() > max_history) history_.pop_front();
    }
    if (coupler_ == nullptr) return;
    switch (id) {
        case Id::event:
            coupler_->set_event_number(v);
            break;
        case Id::barrier:
            coupler_->set_barrier_number(v);
            break;
        case Id::running:
            coupler_->set_running(v != 0);
            break;
        case Id::heartbeat_out:
            if (changed && now - last_hb_edge_ >= heartbeat_filter_) {
                coupler_->toggle_robot_heartbeat();
                last_hb_edge_ = now;
            }
            break;
        default:
            break;
    }
}

std::vector<SignalWrite> CellSignals::output_history() const {
    std::lock_guard lock(values_mu_);
    return {history_.begin(), history_.end()};
}

}  // namespace fibrecell::drivers::sim
