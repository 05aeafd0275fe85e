#include "daemon/log/log_component.hpp"

#include "daemon/log/log_feed.hpp"

namespace fibrecell::daemon::logs {

LogComponent::~LogComponent() { stop(); }

void LogComponent::register_endpoints(component::Endpoints& endpoints) {
    endpoints.event(api::notify::log);
    endpoints_ = endpoints;
}

void LogComponent::start() {
    feed_log_to([endpoints = endpoints_](nlohmann::json line) {
        endpoints.publish({.topic = api::topic::log,
                           .method = api::notify::log,
                           .params = std::move(line),
                           .delivery = api::Delivery::every});
    });
}

void LogComponent::stop() { feed_log_to(nullptr); }

}  // namespace fibrecell::daemon::logs
