#include "drivers/abb/rws/rws_client.hpp"

#include <spdlog/spdlog.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <atomic>
#include <cctype>
#include <map>
#include <mutex>
#include <optional>

#include "drivers/abb/rws/digest.hpp"
#include "drivers/abb/rws/rws_json.hpp"
#include "drivers/abb/rws/url.hpp"

namespace fibrecell::drivers::abb::rws {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

namespace {

constexpr std::string_view session_cookie = "-http-session-";
constexpr std::uint64_t max_response_bytes = 64u << 20;

std::string_view sv(beast::string_view s) {
    return {s.data(), s.size()};
}

struct Reply {
    unsigned status = 0;
    std::string reason;
    std::string body;
};

// RAPID identifiers only: they become path segments.
void check_identifier(const std::string& name, const char* what) {
    bool ok = !name.empty() && name.size() <= 32 &&
              std::isalpha(static_cast<unsigned char>(name.front())) != 0;
    for (const char c : name)
        ok = ok && (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_');
    if (!ok) throw std::invalid_argument(std::string(what) + " '" + name + "' is not a RAPID name");
}

void check_home_path(const std::string& path) {
    if (path.empty() || path.front() == '/' || path.find("..") != std::string::npos ||
        path.find('\\') != std::string::npos)
        throw std::invalid_argument("'" + path + "' is not a file path relative to HOME");
}

bool is_closed_connection(const beast::error_code& ec) {
    return ec == http::error::end_of_stream || ec == asio::error::eof ||
           ec == asio::error::connection_reset || ec == asio::error::broken_pipe ||
           ec == asio::error::connection_aborted;
}

std::string controller_message(const Reply& r) {
    if (const auto s = json::parse_status(r.body); s && !s->msg.empty()) return s->msg;
    return {};
}

}  // namespace

struct RwsClient::Impl {
    RwsClientConfig config;
    std::string endpoint;
    asio::io_context io;
    beast::tcp_stream stream{io};
    beast::flat_buffer buffer;
    bool connected = false;
    DigestSession digest;
    std::map<std::string, std::string> cookies;
    RwsClientStats stats;
    std::atomic<bool> holds_mastership{false};
    mutable std::mutex mu;

    explicit Impl(RwsClientConfig c)
        : config(std::move(c)),
          endpoint(config.host + ":" + std::to_string(config.port)),
          digest(config.user, config.password) {}

    // Runs one asynchronous operation to completion on the private io_context; the stream's
    // deadline bounds it.
    template <class Start>
    beast::error_code run(Start start) {
        beast::error_code result = asio::error::would_block;
        start([&result](beast::error_code ec, auto&&...) { result = ec; });
        io.restart();
        io.run();
        return result;
    }

    void close() {
        beast::error_code ec;
        stream.socket().shutdown(tcp::socket::shutdown_both, ec);
        stream.close();
        buffer.consume(buffer.size());
        connected = false;
    }

    [[noreturn]] void fail_transport(std::string_view what, const std::string& why) {
        throw RwsError(RwsErrorKind::transport, std::string(what) + " at " + endpoint + ": " + why);
    }

    void connect(std::string_view what) {
        tcp::resolver resolver(io);
        beast::error_code ec;
        const auto endpoints = resolver.resolve(config.host, std::to_string(config.port), ec);
        if (ec) fail_transport(what, "cannot resolve host " + config.host + ": " + ec.message());
        stream.expires_after(config.connect_timeout);
        ec = run([&](auto handler) { stream.async_connect(endpoints, std::move(handler)); });
        if (ec == beast::error::timeout)
            fail_transport(what, "no connection within " +
                                     std::to_string(config.connect_timeout.count()) + " ms");
        if (ec) fail_transport(what, "cannot connect: " + ec.message());
        stream.socket().set_option(tcp::no_delay(true), ec);
        connected = true;
        ++stats.connects;
    }

    // One request and its response, reopening a keep-alive connection the server has closed.
    http::response<http::string_body> send(http::request<http::string_body>& req,
                                           std::string_view what) {
        for (int round = 0;; ++round) {
            const bool reused = connected;
            if (!connected) connect(what);
            const auto deadline = std::chrono::steady_clock::now() + config.request_timeout;
            stream.expires_at(deadline);
            ++stats.requests;
            beast::error_code ec =
                run([&](auto handler) { http::async_write(stream, req, std::move(handler)); });
            http::response_parser<http::string_body> parser;
            parser.body_limit(max_response_bytes);
            if (!ec) {
                stream.expires_at(deadline);
                ec = run([&](auto handler) {
                    http::async_read(stream, buffer, parser, std::move(handler));
                });
            }
            if (!ec) {
                auto res = parser.release();
                if (!res.keep_alive()) close();
                return res;
            }
            close();
            if (reused && round == 0 && is_closed_connection(ec)) {
                spdlog::debug("robot.rws_reconnect {} after: {}", endpoint, ec.message());
                continue;
            }
            const std::string request =
                std::string(req.method_string()) + " " + std::string(req.target());
            if (ec == beast::error::timeout)
                fail_transport(what, "no response within " +
                                         std::to_string(config.request_timeout.count()) +
                                         " ms to " + request);
            fail_transport(what, "connection failed during " + request + ": " + ec.message());
        }
    }

    std::string cookie_header() const {
        std::string out;
        for (const auto& [name, value] : cookies) {
            if (!out.empty()) out += "; ";
            out += name + "=" + value;
        }
        return out;
    }

    void keep_cookies(const http::response<http::string_body>& res) {
        const auto range = res.equal_range(http::field::set_cookie);
        for (auto it = range.first; it != range.second; ++it) {
            const std::string_view v = sv(it->value());
            const std::string_view pair = v.substr(0, v.find(';'));
            const auto eq = pair.find('=');
            if (eq == std::string_view::npos || eq == 0) continue;
            cookies[std::string(pair.substr(0, eq))] = std::string(pair.substr(eq + 1));
        }
    }

    std::optional<DigestChallenge> challenge_of(const http::response<http::string_body>& res) {
        const auto range = res.equal_range(http::field::www_authenticate);
        for (auto it = range.first; it != range.second; ++it)
            if (auto c = parse_challenge(sv(it->value()))) return c;
        return std::nullopt;
    }

    // An authenticated exchange: answers the digest challenge, retries once on a stale nonce.
    Reply call(http::verb verb, const std::string& target, std::string body,
               std::string_view content_type, std::string_view what) {
        std::lock_guard lock(mu);
        bool stale_retried = false;
        for (int attempt = 0; attempt < 4; ++attempt) {
            http::request<http::string_body> req(verb, target, 11);
            req.set(http::field::host, endpoint);
            req.set(http::field::user_agent, "fibrecell-rws");
            req.keep_alive(true);
            if (!cookies.empty()) req.set(http::field::cookie, cookie_header());
            const bool with_credentials =
                cookies.count(std::string(session_cookie)) == 0 && digest.has_challenge();
            if (with_credentials)
                req.set(http::field::authorization,
                        digest.authorization(sv(http::to_string(verb)), target));
            if (!body.empty() || verb == http::verb::post || verb == http::verb::put) {
                req.set(http::field::content_type,
                        beast::string_view(content_type.data(), content_type.size()));
                req.body() = body;
            }
            req.prepare_payload();

            auto res = send(req, what);
            keep_cookies(res);
            if (res.result() != http::status::unauthorized)
                return {res.result_int(), std::string(res.reason()), std::move(res.body())};

            const auto challenge = challenge_of(res);
            if (!challenge)
                throw RwsError(RwsErrorKind::protocol,
                               std::string(what) + " at " + endpoint +
                                   ": answered 401 without a digest challenge",
                               401);
            const auto auth_failed = [&] {
                return RwsError(RwsErrorKind::auth,
                                "authentication failed for user " + config.user + " at " +
                                    endpoint + ": wrong user name or password (while trying to " +
                                    std::string(what) + ")",
                                401);
            };
            if (with_credentials && !challenge->stale) throw auth_failed();
            if (challenge->stale) {
                if (stale_retried) throw auth_failed();
                stale_retried = true;
                ++stats.stale_retries;
            }
            cookies.clear();  // the session (if any) is gone
            try {
                digest.accept(*challenge);
            } catch (const std::invalid_argument& e) {
                throw RwsError(RwsErrorKind::protocol,
                               std::string(what) + " at " + endpoint + ": " + e.what(), 401);
            }
            ++stats.challenges;
        }
        throw RwsError(RwsErrorKind::auth,
                       "authentication failed for user " + config.user + " at " + endpoint +
                           ": the controller keeps asking for credentials (while trying to " +
                           std::string(what) + ")",
                       401);
    }

    Reply get(const std::string& target, std::string_view what) {
        return call(http::verb::get, target, {}, {}, what);
    }
    Reply post(const std::string& target, const FormFields& form, std::string_view what) {
        return call(http::verb::post, target, form_encode(form),
                    "application/x-www-form-urlencoded", what);
    }

    // Maps a failed reply to RwsError; returns when `r.status` is one of `ok`.
    void expect(const Reply& r, std::initializer_list<unsigned> ok, std::string_view what) {
        for (const unsigned s : ok)
            if (r.status == s) return;
        const std::string msg = controller_message(r);
        const std::string head = std::string(what) + " at " + endpoint + ": ";
        const std::string detail = msg.empty() ? "" : " (controller: " + msg + ")";
        switch (r.status) {
            case 403: {
                const std::string why = holds_mastership
                                            ? "RAPID mastership is held by another client"
                                            : "RAPID mastership is not held by this client "
                                              "(request it first)";
                throw RwsError(RwsErrorKind::mastership, head + why + (msg == why ? "" : detail),
                               403);
            }
            case 404:
                throw RwsError(RwsErrorKind::not_found,
                               head + "not found" + (msg.empty() ? "" : ": " + msg), 404);
            case 400:
            case 409:
                throw RwsError(RwsErrorKind::state,
                               head + "the controller refused" + (msg.empty() ? "" : ": " + msg),
                               static_cast<int>(r.status));
            default:
                throw RwsError(
                    RwsErrorKind::protocol,
                    head + "unexpected HTTP " + std::to_string(r.status) + " " + r.reason + detail,
                    static_cast<int>(r.status));
        }
    }

    // The `_embedded._state` items of a JSON reply.
    json::Json items(const Reply& r, std::string_view what) {
        const json::Json doc = json::Json::parse(r.body, nullptr, false);
        try {
            if (doc.is_discarded()) throw std::runtime_error("the response is not JSON");
            return json::state_items(doc);
        } catch (const std::exception& e) {
            throw RwsError(
                RwsErrorKind::protocol,
                std::string(what) + " at " + endpoint + ": unreadable response (" + e.what() + ")",
                static_cast<int>(r.status));
        }
    }

    std::string field(const json::Json& items, std::string_view key, std::string_view what) {
        if (!items.empty())
            if (auto v = json::text_field(items.front(), key)) return *v;
        throw RwsError(RwsErrorKind::protocol, std::string(what) + " at " + endpoint +
                                                   ": the response has no '" + std::string(key) +
                                                   "'");
    }

    std::vector<BuildError> build_errors(std::string_view what) {
        const Reply r = get("/rw/rapid/tasks/" + config.task + "/program/builderror?json=1", what);
        expect(r, {200}, what);
        std::vector<BuildError> out;
        for (const auto& item : items(r, what)) {
            BuildError e;
            e.module = json::text_field(item, "ModuleName").value_or("");
            const auto number = [&](const char* k) -> std::size_t {
                try {
                    return std::stoul(json::text_field(item, k).value_or("0"));
                } catch (const std::exception&) {
                    return 0;
                }
            };
            e.row = number("row");
            e.column = number("column");
            e.message = json::text_field(item, "error").value_or("");
            out.push_back(std::move(e));
        }
        return out;
    }

    std::string symbol_target(const std::string& module, const std::string& name) const {
        return "/rw/rapid/symbol/data/RAPID/" + config.task + "/" + module + "/" + name;
    }
};

RwsClient::RwsClient(RwsClientConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {
    check_identifier(impl_->config.task, "task");
}

RwsClient::~RwsClient() = default;

std::string RwsClient::endpoint() const {
    return impl_->endpoint;
}

bool RwsClient::holds_mastership() const {
    return impl_->holds_mastership;
}

RwsClientStats RwsClient::stats() const {
    std::lock_guard lock(impl_->mu);
    return impl_->stats;
}

void RwsClient::upload_file(const std::string& path, std::string_view contents) {
    check_home_path(path);
    const std::string what = "upload HOME:/" + path;
    const Reply r = impl_->call(http::verb::put, "/fileservice/$HOME/" + percent_encode(path, "/"),
                                std::string(contents), "text/plain", what);
    impl_->expect(r, {200, 201, 204}, what);
}

std::string RwsClient::download_file(const std::string& path) {
    check_home_path(path);
    const std::string what = "download HOME:/" + path;
    const Reply r = impl_->get("/fileservice/$HOME/" + percent_encode(path, "/"), what);
    impl_->expect(r, {200}, what);
    return r.body;
}

void RwsClient::load_module(const std::string& path, bool replace) {
    check_home_path(path);
    const std::string modulepath = "$HOME/" + path;
    const std::string what = "load module " + modulepath + " into " + impl_->config.task;
    const Reply r =
        impl_->post("/rw/rapid/tasks/" + impl_->config.task + "?action=loadmod",
                    {{"modulepath", modulepath}, {"replace", replace ? "true" : "false"}}, what);
    const bool loaded = r.status == 200 || r.status == 204;
    if (!loaded && r.status != 400 && r.status != 409) impl_->expect(r, {200, 204}, what);

    // The build log says why a load failed, or that a loaded module does not build.
    std::vector<BuildError> log;
    try {
        log = impl_->build_errors(what);
    } catch (const RwsError& e) {
        if (loaded || e.kind() == RwsErrorKind::transport || e.kind() == RwsErrorKind::auth) throw;
    }
    if (log.empty()) {
        if (!loaded) impl_->expect(r, {200, 204}, what);
        return;
    }
    const BuildError& first = log.front();
    std::string msg = what + " at " + impl_->endpoint + ": build error in " + format(first);
    if (log.size() > 1) msg += " (and " + std::to_string(log.size() - 1) + " more)";
    if (loaded) msg += "; the module is loaded but the program does not build";
    throw RwsError(RwsErrorKind::build, msg, static_cast<int>(r.status), std::move(log));
}

void RwsClient::unload_module(const std::string& module) {
    check_identifier(module, "module");
    const std::string what = "unload module " + module + " from " + impl_->config.task;
    const Reply r = impl_->post("/rw/rapid/tasks/" + impl_->config.task + "?action=unloadmod",
                                {{"module", module}}, what);
    impl_->expect(r, {200, 204}, what);
}

std::vector<ModuleInfo> RwsClient::modules() {
    const std::string what = "list the modules of " + impl_->config.task;
    const Reply r = impl_->get("/rw/rapid/modules?task=" + impl_->config.task + "&json=1", what);
    impl_->expect(r, {200}, what);
    std::vector<ModuleInfo> out;
    for (const auto& item : impl_->items(r, what)) {
        ModuleInfo m;
        m.name = json::text_field(item, "name").value_or("");
        m.type = json::text_field(item, "type").value_or("");
        if (!m.name.empty()) out.push_back(std::move(m));
    }
    return out;
}

std::vector<BuildError> RwsClient::build_errors() {
    return impl_->build_errors("read the build log of " + impl_->config.task);
}

void RwsClient::start_execution(const StartOptions& o) {
    const std::string what = "start RAPID execution";
    const Reply r = impl_->post("/rw/rapid/execution?action=start",
                                {{"regain", o.regain},
                                 {"execmode", o.execmode},
                                 {"cycle", o.cycle},
                                 {"condition", o.condition},
                                 {"stopatbp", o.stopatbp},
                                 {"alltaskbytsp", o.alltaskbytsp}},
                                what);
    impl_->expect(r, {200, 204}, what);
}

void RwsClient::stop_execution() {
    const std::string what = "stop RAPID execution";
    const Reply r = impl_->post("/rw/rapid/execution?action=stop",
                                {{"stopmode", "stop"}, {"usetsp", "normal"}}, what);
    impl_->expect(r, {200, 204}, what);
}

void RwsClient::reset_program_pointer() {
    const std::string what = "reset the program pointer to main";
    const Reply r = impl_->post("/rw/rapid/execution?action=resetpp", {}, what);
    impl_->expect(r, {200, 204}, what);
}

void RwsClient::request_mastership() {
    const std::string what = "request RAPID mastership";
    const Reply r = impl_->post("/rw/mastership?action=request", {}, what);
    if (r.status == 403 || r.status == 409) {
        const std::string msg = controller_message(r);
        throw RwsError(RwsErrorKind::mastership,
                       what + " at " + impl_->endpoint +
                           ": RAPID mastership is held by another client" +
                           (msg.empty() || msg == "RAPID mastership is held by another client"
                                ? ""
                                : " (controller: " + msg + ")"),
                       static_cast<int>(r.status));
    }
    impl_->expect(r, {200, 204}, what);
    impl_->holds_mastership = true;
}

void RwsClient::release_mastership() {
    const std::string what = "release RAPID mastership";
    const Reply r = impl_->post("/rw/mastership?action=release", {}, what);
    impl_->expect(r, {200, 204}, what);
    impl_->holds_mastership = false;
}

ExecutionInfo RwsClient::execution_state() {
    const std::string what = "read the RAPID execution state";
    const Reply r = impl_->get("/rw/rapid/execution?json=1", what);
    impl_->expect(r, {200}, what);
    const auto it = impl_->items(r, what);
    const std::string state = impl_->field(it, "ctrlexecstate", what);
    const auto parsed = parse_execution_state(state);
    if (!parsed)
        throw RwsError(RwsErrorKind::protocol, what + " at " + impl_->endpoint +
                                                   ": unknown execution state '" + state + "'");
    ExecutionInfo out;
    out.state = *parsed;
    out.cycle = json::text_field(it.front(), "cycle").value_or("");
    return out;
}

ControllerState RwsClient::controller_state() {
    const std::string what = "read the controller state";
    const Reply r = impl_->get("/rw/panel/ctrlstate?json=1", what);
    impl_->expect(r, {200}, what);
    const std::string state = impl_->field(impl_->items(r, what), "ctrlstate", what);
    const auto parsed = parse_controller_state(state);
    if (!parsed)
        throw RwsError(RwsErrorKind::protocol, what + " at " + impl_->endpoint +
                                                   ": unknown controller state '" + state + "'");
    return *parsed;
}

void RwsClient::set_symbol(const std::string& module, const std::string& name,
                           const std::string& value) {
    check_identifier(module, "module");
    check_identifier(name, "symbol");
    const std::string what = "write RAPID data " + module + "/" + name;
    const Reply r =
        impl_->post(impl_->symbol_target(module, name) + "?action=set", {{"value", value}}, what);
    impl_->expect(r, {200, 204}, what);
}

std::string RwsClient::symbol(const std::string& module, const std::string& name) {
    check_identifier(module, "module");
    check_identifier(name, "symbol");
    const std::string what = "read RAPID data " + module + "/" + name;
    const Reply r = impl_->get(impl_->symbol_target(module, name) + "?json=1", what);
    impl_->expect(r, {200}, what);
    return impl_->field(impl_->items(r, what), "value", what);
}

void RwsClient::logout() {
    const std::string what = "log out";
    {
        std::lock_guard lock(impl_->mu);
        if (impl_->cookies.empty() && !impl_->digest.has_challenge()) return;
    }
    const Reply r = impl_->get("/logout", what);
    impl_->expect(r, {200, 204}, what);
    std::lock_guard lock(impl_->mu);
    impl_->cookies.clear();
    impl_->digest.forget();
    impl_->holds_mastership = false;
    impl_->close();
}

}  // namespace fibrecell::drivers::abb::rws
