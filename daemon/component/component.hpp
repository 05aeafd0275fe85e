#pragma once
// A part of the service that owns one concern's state and its endpoints (docs/layout.md,
// "Components"): Cell (the devices), Jobs (the store and planning), Printer (the print on the
// cell) and Log. The service lists its components once (daemon/service/service.cpp), in the order
// they depend on each other; a component that must have a say in another's work registers on the
// hooks its owner offers (the printer's start gates, the cell's status parts), in its constructor.
//
// Life: register_endpoints (in order, before anything listens), start (in order: load state,
// build what the component owns), the API and dashboard listen, serve (in order: connect devices,
// resume work), ... stop (in reverse order: no new work, the print paused), join (in reverse
// order: wait for what is still running, up to a deadline).

#include "daemon/component/endpoints.hpp"

#include <chrono>

namespace fibrecell::daemon::component {

class Component {
  public:
    using Deadline = std::chrono::steady_clock::time_point;

    virtual ~Component() = default;

    virtual void register_endpoints(Endpoints& endpoints) = 0;
    virtual void start() {}
    virtual void serve() {}
    virtual void stop() {}
    // False: something did not end by the deadline (the caller ends the process without it).
    virtual bool join(Deadline) { return true; }
};

}  // namespace fibrecell::daemon::component
