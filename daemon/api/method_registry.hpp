#pragma once
// Method handlers by name. Sync handlers return the result (or throw ApiError); async handlers
// get a Responder they may complete later from any thread. Built-in methods (server.auth,
// subscribe, unsubscribe) and "rpc.*" are reserved.

#include "daemon/api/call_context.hpp"
#include "daemon/api/responder.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <set>
#include <string>

namespace fibrecell::api {

using SyncHandler =
    std::function<nlohmann::json(const nlohmann::json& params, const CallContext& ctx)>;
using AsyncHandler =
    std::function<void(const nlohmann::json& params, const CallContext& ctx, Responder responder)>;

class MethodRegistry {
  public:
    // Throw std::logic_error for a reserved, empty or already registered name.
    void add(std::string name, SyncHandler handler);
    void add_async(std::string name, AsyncHandler handler);

    const AsyncHandler* find(const std::string& name) const;  // nullptr when unknown
    // Control methods stay callable from the reserved capacity (ApiConfig::reserved_control_clients).
    void mark_control(const std::string& name);
    bool is_control(const std::string& name) const;
    std::string control_names() const;  // "cell.status, job.pause, ..." for messages
    static bool reserved(const std::string& name);

  private:
    std::map<std::string, AsyncHandler, std::less<>> handlers_;
    std::set<std::string, std::less<>> control_;
};

}  // namespace fibrecell::api
