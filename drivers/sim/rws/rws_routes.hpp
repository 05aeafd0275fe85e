#pragma once
// Internal to RwsServer: the RWS 1.0 resources the simulator serves, mapped onto an RwsBackend.
// Authentication and sessions are done before route() is called; mastership is the server's
// bookkeeping, seen from the calling session through MastershipGate.
//
//   PUT|GET /fileservice/$HOME/<path>                        file upload / download
//   POST    /rw/rapid/tasks/<task>?action=loadmod|unloadmod  modulepath=$HOME/x.mod&replace=true
//                                                            | module=<name>          [mastership]
//   GET     /rw/rapid/modules?task=<task>                    rap-module-info-li items
//   GET     /rw/rapid/tasks/<task>/program/builderror        rap-builderrs items
//   POST    /rw/rapid/execution?action=start|stop|resetpp    resetpp needs mastership
//   GET     /rw/rapid/execution                              rap-execution: ctrlexecstate, cycle
//   GET     /rw/panel/ctrlstate                              pnl-ctrlstate: ctrlstate
//   POST    /rw/mastership?action=request|release
//   GET     /rw/rapid/symbol/data/RAPID/<task>/<module>/<name>   rap-data: value
//   POST    ...same...?action=set  value=<RAPID text>        [mastership]
// Successful actions answer 204; reads answer 200 with the JSON of rws_json.hpp.

#include <string>
#include <string_view>

#include "drivers/sim/rws/rws_backend.hpp"

namespace fibrecell::drivers::sim::rws {

class MastershipGate {
  public:
    virtual ~MastershipGate() = default;
    virtual bool held_by_caller() const = 0;
    virtual bool held_elsewhere() const = 0;
    virtual bool request() = 0;  // false when another client holds it
    virtual void release() = 0;
};

struct RouteRequest {
    std::string_view method;  // "GET", "PUT", "POST", ...
    std::string_view target;  // as received: path and query
    std::string_view body;
    std::string_view host;  // Host header, for the _links base
};

struct RouteReply {
    unsigned status = 200;
    std::string body;
    std::string content_type = "application/json";
};

RouteReply route(const RouteRequest& request, RwsBackend& backend, MastershipGate& mastership,
                 std::string_view task);

}  // namespace fibrecell::drivers::sim::rws
