#pragma once
// Method handlers by name, each with the component that owns it, and the events each component
// publishes: the service's one registry of what its clients can call and hear (docs/socket-api.md
// lists the same). Sync handlers return the result (or throw ApiError); async handlers get a
// Responder they may complete later from any thread. Built-in methods (server.auth, subscribe,
// unsubscribe) and "rpc.*" are reserved.

#include "daemon/api/call_context.hpp"
#include "daemon/api/responder.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace fibrecell::api {

using SyncHandler =
    std::function<nlohmann::json(const nlohmann::json& params, const CallContext& ctx)>;
using AsyncHandler =
    std::function<void(const nlohmann::json& params, const CallContext& ctx, Responder responder)>;

// One entry of the registry's list. The built-in methods' owner is "api".
struct Registration {
    std::string name;
    std::string owner;
    bool control = false;  // for methods
};

class MethodRegistry {
  public:
    // Throw std::logic_error for a reserved, empty or already registered name. `owner`: the
    // component that answers it (empty for a test's own server).
    void add(std::string name, SyncHandler handler, std::string owner = {});
    void add_async(std::string name, AsyncHandler handler, std::string owner = {});
    // An event (notify.*) `owner` publishes; a second owner of the same event is added beside.
    void add_event(std::string name, std::string owner);

    const AsyncHandler* find(const std::string& name) const;  // nullptr when unknown
    // Control methods stay callable from the reserved capacity (ApiConfig::reserved_control_clients).
    void mark_control(const std::string& name);
    bool is_control(const std::string& name) const;
    std::string control_names() const;  // "cell.status, job.pause, ..." for messages
    static bool reserved(const std::string& name);

    // Every method, built-in ones included, and every event, by name.
    std::vector<Registration> methods() const;
    std::vector<Registration> events() const;

  private:
    std::map<std::string, AsyncHandler, std::less<>> handlers_;
    std::map<std::string, std::string, std::less<>> owners_;
    std::set<std::pair<std::string, std::string>> events_;  // (name, owner)
    std::set<std::string, std::less<>> control_;
};

}  // namespace fibrecell::api
