#include "daemon/component/endpoints.hpp"

#include "daemon/api/api_server.hpp"
#include "daemon/http/http_server.hpp"

namespace fibrecell::daemon::component {

Endpoints::Endpoints(api::ApiServer& api, http::HttpServer* http, std::string owner)
    : api_(&api), http_(http), owner_(std::move(owner)) {}

void Endpoints::method(std::string name, api::SyncHandler handler) {
    api_->add_method(std::move(name), std::move(handler), owner_);
}

void Endpoints::control_method(std::string name, api::SyncHandler handler) {
    const std::string n = name;
    api_->add_method(std::move(name), std::move(handler), owner_);
    api_->add_control_method(n);
}

void Endpoints::event(std::string notify_method) { api_->add_event(std::move(notify_method), owner_); }

void Endpoints::file_route(std::string prefix, http::FileResolver resolver) {
    if (http_) http_->add_file_route(std::move(prefix), std::move(resolver));
}

void Endpoints::publish(api::ApiEvent event) const {
    if (api_) api_->publish(std::move(event));
}

}  // namespace fibrecell::daemon::component
