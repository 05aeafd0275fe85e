#include "daemon/api/method_registry.hpp"

#include <stdexcept>

namespace fibrecell::api {

bool MethodRegistry::reserved(const std::string& name) {
    return name == "server.auth" || name == "subscribe" || name == "unsubscribe" ||
           name.rfind("rpc.", 0) == 0;
}

void MethodRegistry::add(std::string name, SyncHandler handler, std::string owner) {
    if (!handler) throw std::logic_error("api method " + name + ": empty handler");
    // A sync handler answers before it returns; the dispatcher turns a throw into an error.
    add_async(std::move(name),
              [h = std::move(handler)](const nlohmann::json& params, const CallContext& ctx,
                                       Responder r) { r.result(h(params, ctx)); },
              std::move(owner));
}

void MethodRegistry::add_async(std::string name, AsyncHandler handler, std::string owner) {
    if (name.empty()) throw std::logic_error("api method: empty name");
    if (reserved(name)) throw std::logic_error("api method " + name + ": the name is reserved");
    if (!handler) throw std::logic_error("api method " + name + ": empty handler");
    if (!handlers_.emplace(name, std::move(handler)).second)
        throw std::logic_error("api method " + name + ": registered twice");
    owners_.emplace(std::move(name), std::move(owner));
}

void MethodRegistry::add_event(std::string name, std::string owner) {
    if (name.empty()) throw std::logic_error("api event: empty name");
    events_.emplace(std::move(name), std::move(owner));
}

std::vector<Registration> MethodRegistry::methods() const {
    std::vector<Registration> out;
    for (const char* builtin : {"server.auth", "subscribe", "unsubscribe"})
        out.push_back({builtin, "api", is_control(builtin)});
    for (const auto& [name, owner] : owners_) out.push_back({name, owner, is_control(name)});
    return out;
}

std::vector<Registration> MethodRegistry::events() const {
    std::vector<Registration> out;
    for (const auto& [name, owner] : events_) out.push_back({name, owner});
    return out;
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
