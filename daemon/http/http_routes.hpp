#pragma once
// Internal: the dashboard's HTTP answers that are not files: the login, the session, errors.
// Every answer carries the same protective headers (no sniffing, no framing, no referrer).

#include "daemon/http/http_core.hpp"

#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>

#include <string>

namespace fibrecell::http {

using Request = boost::beast::http::request<boost::beast::http::string_body>;
using TextResponse = boost::beast::http::response<boost::beast::http::string_body>;

inline constexpr const char* kSessionCookie = "fibrecell_session";
inline constexpr std::size_t kMaxBodyBytes = 64 * 1024;  // the login's JSON; files go over the API

// The headers every answer has; `version`/`keep_alive` from the request.
template <class Response>
void add_common_headers(Response& res, const Request& req) {
    namespace http = boost::beast::http;
    res.version(req.version());
    res.keep_alive(req.keep_alive());
    res.set(http::field::server, "fibrecelld");
    res.set("X-Content-Type-Options", "nosniff");
    res.set("X-Frame-Options", "DENY");
    res.set("Referrer-Policy", "no-referrer");
}

// {"error": text} with `status`.
TextResponse json_error(const Request& req, boost::beast::http::status status,
                        const std::string& text);

// The request's session cookie's value ("" without one).
std::string session_id(const Request& req);
// Whether the request's session cookie names a live session.
bool has_session(HttpCore& core, const Request& req);

// POST /api/login {"token": ...}: 200 with the session cookie, 401 for a wrong token, 429 while
// the address has had too many wrong tokens in the last minute.
TextResponse login(HttpCore& core, const Request& req, const std::string& address,
                   const std::string& peer);
// POST /api/logout: the session ends and the cookie is cleared.
TextResponse logout(HttpCore& core, const Request& req);
// GET /api/session: {"authenticated": bool}; the page asks before showing the login.
TextResponse session_state(HttpCore& core, const Request& req);

// A WebSocket from a page of ours: no Origin (not a browser), or one naming this Host.
bool same_origin(const Request& req);

}  // namespace fibrecell::http
