#pragma once
// Log, the component that sends the service's log lines to the API's clients (topic "log",
// notify.log; the dashboard's log page) while the service runs (daemon/log/log_feed.hpp).

#include "daemon/component/component.hpp"

namespace fibrecell::daemon::logs {

class LogComponent : public component::Component {
  public:
    ~LogComponent() override;
    void register_endpoints(component::Endpoints& endpoints) override;
    void start() override;
    void stop() override;

  private:
    component::Endpoints endpoints_;
};

}  // namespace fibrecell::daemon::logs
