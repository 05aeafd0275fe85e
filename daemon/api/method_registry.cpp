#include "daemon/api/method_registry.hpp"

#include <stdexcept>

namespace fibrecell::api {

bool MethodRegistry::reserved(const std::string& name) {
    return name == "server.auth" || name == "subscribe" || name == "unsubscribe" ||
           name.rfind("rpc.", 0) == 0;
}

void MethodRegistry::add(std::string name, SyncHandler handler) {
    if (!handler) throw std::logic_error("api method " + name + ": empty handler");
    // A sync handler answers before it returns; the dispatcher turns a throw into an error.
    add_async(std::move(name),
              [h = std::move(handler)](const nlohmann::json& params, const CallContext& ctx,
                                       Responder r) { r.result(h(params, ctx)); });
}

void MethodRegistry::add_async(std::string name, AsyncHandler handler) {
    if (name.empty()) throw std::logic_error("api method: empty name");
    if (reserved(name)) throw std::logic_error("api method " + name + ": the name is reserved");
    if (!handler) throw std::logic_error("api method " + name + ": empty handler");
    if (!handlers_.emplace(name, std::move(handler)).second)
        throw std::logic_error("api method " + name + ": registered twice");
}

void MethodRegistry::mark_control(const std::string& name) {
    if (!handlers_.contains(name)) throw std::logic_error("api method " + name + ": not registered");
    control_.insert(name);
}

bool MethodRegistry::is_control(const std::string& name) const {
    return name == "server.auth" || control_.contains(name);
}

std::string MethodRegistry::control_names() const {
    std::string s;
    for (const auto& name : control_) s += (s.empty() ? "" : ", ") + name;
    return s.empty() ? "server.auth" : s;
}

const AsyncHandler* MethodRegistry::find(const std::string& name) const {
    const auto it = handlers_.find(name);
    return it == handlers_.end() ? nullptr : &it->second;
}

}  // namespace fibrecell::api
