#include "daemon/http/http_routes.hpp"

#include "daemon/api/token.hpp"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

namespace fibrecell::http {

namespace beast = boost::beast;
namespace bhttp = beast::http;
using nlohmann::json;

namespace {

TextResponse json_response(const Request& req, bhttp::status status, const json& body) {
    TextResponse res{status, req.version()};
    add_common_headers(res, req);
    res.set(bhttp::field::content_type, "application/json");
    res.set(bhttp::field::cache_control, "no-store");
    res.body() = body.dump();
    res.prepare_payload();
    return res;
}

std::string session_cookie(const std::string& value, long max_age_s, bool secure) {
    return std::string(kSessionCookie) + "=" + value + "; Path=/; Max-Age=" +
           std::to_string(max_age_s) + "; HttpOnly; SameSite=Strict" + (secure ? "; Secure" : "");
}

}  // namespace

std::string session_id(const Request& req) {
    const auto it = req.find(bhttp::field::cookie);
    if (it == req.end()) return "";
    return cookie_value(std::string_view(it->value().data(), it->value().size()), kSessionCookie);
}

TextResponse json_error(const Request& req, bhttp::status status, const std::string& text) {
    return json_response(req, status, json{{"error", text}});
}

bool has_session(HttpCore& core, const Request& req) {
    const std::string id = session_id(req);
    if (id.empty()) return false;
    const std::lock_guard lock(core.mutex);
    return core.sessions.valid(id, Clock::now());
}

TextResponse login(HttpCore& core, const Request& req, const std::string& address,
                   const std::string& peer) {
    std::string token;
    try {
        const json body = json::parse(req.body());
        if (!body.is_object() || !body.contains("token") || !body["token"].is_string())
            return json_error(req, bhttp::status::bad_request,
                              "login: the body must be {\"token\": \"...\"}");
        token = body["token"].get<std::string>();
    } catch (const json::parse_error&) {
        return json_error(req, bhttp::status::bad_request, "login: the body is not JSON");
    }
    const auto now = Clock::now();
    const std::lock_guard lock(core.mutex);
    if (const auto wait = core.guard.wait_for(address, now)) {
        core.counters.login_throttled++;
        spdlog::warn("http.login_throttled peer={} retry_after_s={}", peer, wait->count());
        TextResponse res = json_error(
            req, bhttp::status::too_many_requests,
            "too many wrong tokens from " + address + "; try again in " +
                std::to_string(wait->count()) + " s");
        res.set(bhttp::field::retry_after, std::to_string(wait->count()));
        return res;
    }
    if (!api::same_token(token, core.config.http.token)) {
        core.guard.failed(address, now);
        core.counters.login_failures++;
        spdlog::warn("http.login_failed peer={}: wrong token", peer);
        return json_error(req, bhttp::status::unauthorized, "wrong token");
    }
    core.guard.succeeded(address);
    core.counters.logins++;
    const std::string id = core.sessions.open(now);
    const long lifetime = static_cast<long>(core.sessions.lifetime().count());
    spdlog::info("http.login peer={}", peer);
    TextResponse res =
        json_response(req, bhttp::status::ok, json{{"authenticated", true}, {"expires_in_s", lifetime}});
    res.set(bhttp::field::set_cookie, session_cookie(id, lifetime, core.config.http.secure_cookie));
    return res;
}

TextResponse logout(HttpCore& core, const Request& req) {
    const std::string id = session_id(req);
    bool secure = false;
    {
        const std::lock_guard lock(core.mutex);
        if (!id.empty()) core.sessions.close(id);
        secure = core.config.http.secure_cookie;
    }
    TextResponse res = json_response(req, bhttp::status::ok, json{{"authenticated", false}});
    res.set(bhttp::field::set_cookie, session_cookie("", 0, secure));
    return res;
}

TextResponse session_state(HttpCore& core, const Request& req) {
    return json_response(req, bhttp::status::ok, json{{"authenticated", has_session(core, req)}});
}

bool same_origin(const Request& req) {
    const auto origin = req.find(bhttp::field::origin);
    if (origin == req.end()) return true;
    const auto host = req.find(bhttp::field::host);
    if (host == req.end()) return false;
    const std::string o(origin->value());
    const std::string h(host->value());
    return o == "http://" + h || o == "https://" + h;
}

}  // namespace fibrecell::http
