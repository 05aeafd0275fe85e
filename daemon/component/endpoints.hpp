#pragma once
// What one component of the service offers its clients: the API methods it answers, the events it
// publishes and the dashboard files it serves, each registered under the component's name on the
// service's one registry (the API server's) before the listeners start. docs/socket-api.md lists
// every method and event with its owner; tests/service/registry_test.cpp checks that the two agree.
//
//   void Jobs::register_endpoints(component::Endpoints& e) {
//       e.method("job.list", [this](const json& params, const api::CallContext& ctx) { ... });
//       e.event(api::notify::job_state);
//       endpoints_ = e;  // to publish later, from any thread
//   }

#include "daemon/api/api_event.hpp"
#include "daemon/api/method_registry.hpp"
#include "daemon/http/file_route.hpp"

#include <string>

namespace fibrecell::api {
class ApiServer;
}
namespace fibrecell::http {
class HttpServer;
}

namespace fibrecell::daemon::component {

class Endpoints {
  public:
    Endpoints() = default;  // publishes nowhere, until a registration assigns it
    // `http` is null when the dashboard is off (api.http): file routes are then not served.
    Endpoints(api::ApiServer& api, http::HttpServer* http, std::string owner);

    void method(std::string name, api::SyncHandler handler);
    // A method the operator must reach even when api.max_clients connections are taken (status,
    // pause, abort, E-stop; docs/socket-api.md, "Connecting").
    void control_method(std::string name, api::SyncHandler handler);
    // An event (api::notify::*) this component publishes.
    void event(std::string notify_method);
    // The dashboard's files behind the login under `prefix` (http::HttpServer::add_file_route).
    void file_route(std::string prefix, http::FileResolver resolver);

    // Sends an event to its subscribers; thread-safe. Nothing before registration.
    void publish(api::ApiEvent event) const;

    const std::string& owner() const { return owner_; }

  private:
    api::ApiServer* api_ = nullptr;
    http::HttpServer* http_ = nullptr;
    std::string owner_;
};

}  // namespace fibrecell::daemon::component
