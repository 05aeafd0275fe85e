#include "daemon/devices/cell_component.hpp"

#include "config/thread_priority.hpp"
#include "daemon/api/params.hpp"

#include <spdlog/spdlog.h>

namespace fibrecell::daemon::devices {

using api::CallContext;
using nlohmann::json;

CellComponent::CellComponent(boost::asio::io_context& io, const CellConfig& cell,
                             CellComponentOptions options)
    : cell_(cell), options_(options), ticker_(io) {}

CellComponent::~CellComponent() = default;

void CellComponent::add_status_part(StatusPart part) { status_parts_.push_back(std::move(part)); }

void CellComponent::on_estop(std::function<void()> after) { on_estop_.push_back(std::move(after)); }

void CellComponent::register_endpoints(component::Endpoints& endpoints) {
    endpoints.control_method("cell.status", [this](const json& params, const CallContext& ctx) {
        api::ParamReader(ctx.method, params).finish();
        return status();
    });

    endpoints.control_method("cell.estop", [this](const json& params, const CallContext& ctx) {
        api::ParamReader(ctx.method, params).finish();
        spdlog::critical("cell.estop requested by {}", ctx.peer);
        devices_->estop();
        for (const auto& after : on_estop_) after();
        std::string note = "M112 sent and robot abort requested; not a safety function";
        if (!devices_->board().emergency_parser())
            note += "; this board's firmware has no emergency parser: it obeys M112 only after "
                    "a blocking command (a heat-up) ends";
        return json{{"estop", true}, {"note", note}};
    });

    endpoints.event(api::notify::cell_status);
    endpoints_ = endpoints;
}

void CellComponent::start() {
    // Before the devices start their threads (config/thread_priority.hpp).
    config::set_time_critical_priority(options_.realtime_priority);
    devices_ = std::make_unique<CellDevices>(cell_);
}

void CellComponent::serve() {
    try {
        devices_->connect(options_.connect_timeout);
        spdlog::info("cell.connected {}", cell_.name);
    } catch (const std::exception& e) {
        spdlog::warn("cell.not_connected {} (a start retries)", e.what());
    }
    tick();
}

void CellComponent::stop() {
    stopping_ = true;
    ticker_.cancel();
    if (devices_) devices_->disconnect();
}

void CellComponent::tick() {
    ticker_.expires_after(std::chrono::milliseconds(500));
    ticker_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopping_) return;
        // The robot's heartbeat proves this loop runs, not just the link's thread.
        devices_->robot_io().service_alive();
        endpoints_.publish({.topic = api::topic::cell,
                            .method = api::notify::cell_status,
                            .params = status(),
                            .delivery = api::Delivery::latest});
        tick();
    });
}

json CellComponent::status() const {
    json s = devices_->status();
    s["name"] = cell_.name;
    s["simulated"] = devices_->simulated();
    s["time_scale"] = devices_->time_scale();
    for (const StatusPart& part : status_parts_) part(s);
    return s;
}

}  // namespace fibrecell::daemon::devices
