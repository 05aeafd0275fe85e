// The JSON-RPC side of a ClientSession: one line -> one request or a batch -> handlers -> answers.
#include "daemon/api/client_session.hpp"

#include "daemon/api/params.hpp"
#include "daemon/api/token.hpp"

#include <spdlog/spdlog.h>
#include <boost/asio/dispatch.hpp>

namespace fibrecell::api {

namespace {

constexpr std::size_t kMaxTopicsPerClient = 1000;
constexpr std::size_t kMaxTopicChars = 200;

}  // namespace

void ClientSession::handle_line(std::string_view line) {
    if (line.find_first_not_of(" \t") == std::string_view::npos) return;  // blank lines are fine
    ParsedLine parsed = parse_line(line);
    if (!parsed.error.is_null()) {
        send(parsed.error);
        return;
    }
    nlohmann::json message = std::move(parsed.message);
    auto reply = std::make_shared<PendingReply>();
    reply->session = weak_from_this();
    if (message.is_array()) {
        if (message.empty()) {
            send(error_response(nullptr, errc::invalid_request, "invalid request: an empty batch"));
            return;
        }
        const auto max_calls = static_cast<std::size_t>(core_->config.max_batch_calls);
        if (message.size() > max_calls) {
            // Refused whole, before any call runs: none of it happened.
            send(error_response(nullptr, errc::invalid_request,
                                "invalid request: a batch of " + std::to_string(message.size()) +
                                    " calls; at most " + std::to_string(max_calls) +
                                    " (api.max_batch_calls)"));
            return;
        }
        reply->batch = true;
        reply->slots.resize(message.size());
        reply->remaining = message.size();
        ++in_flight_;
        // Every entry is answered, even after a wrong token closed the connection mid-batch.
        for (std::size_t i = 0; i < message.size(); ++i) dispatch(std::move(message[i]), reply, i);
    } else {
        reply->slots.resize(1);
        reply->remaining = 1;
        ++in_flight_;
        dispatch(std::move(message), reply, 0);
    }
}

void ClientSession::complete(const std::shared_ptr<PendingReply>& reply, std::size_t slot,
                             std::optional<nlohmann::json> response) {
    reply->slots[slot] = std::move(response);
    if (--reply->remaining != 0) return;
    const auto session = reply->session.lock();
    if (session) --session->in_flight_;
    if (!session || session->closed_) return;  // the client left before its answer was ready
    if (!reply->batch) {
        if (reply->slots[0]) session->send(*reply->slots[0]);
        return;
    }
    nlohmann::json answers = nlohmann::json::array();
    for (auto& s : reply->slots) {
        if (!s) continue;
        if (s->contains("error")) session->core_->counters.errors++;
        answers.push_back(std::move(*s));
    }
    // A batch of notifications only is answered with nothing at all.
    if (answers.empty()) return;
    std::string line = to_line(answers);
    const std::size_t limit = session->core_->config.max_client_queue_bytes;
    if (line.size() > limit)
        // The calls ran; only their answers are too big to send in one go.
        line = to_line(error_response(
            nullptr, errc::too_large,
            "the batch's " + std::to_string(answers.size()) + " answers came to " +
                std::to_string(line.size()) + " bytes, over api.max_client_queue_bytes (" +
                std::to_string(limit) + "); the calls were made: ask for fewer at a time"));
    session->enqueue(std::make_shared<const std::string>(std::move(line)));
}

Responder ClientSession::make_responder(const RpcRequest& request,
                                        const std::shared_ptr<PendingReply>& reply,
                                        std::size_t slot) {
    const bool notification = request.notification;
    std::weak_ptr<ServerCore> weak_core = core_;
    return Responder(
        request.method, request.id,
        [reply, slot, notification, weak_core](nlohmann::json response) {
            const auto core = weak_core.lock();
            if (!core) return;  // the server is gone
            // Inline when already on the strand (sync handlers), else posted.
            boost::asio::dispatch(core->strand, [reply, slot, notification,
                                                 response = std::move(response)]() mutable {
                complete(reply, slot,
                         notification ? std::nullopt
                                      : std::optional<nlohmann::json>(std::move(response)));
            });
        });
}

void ClientSession::dispatch(nlohmann::json&& element, const std::shared_ptr<PendingReply>& reply,
                             std::size_t slot) {
    CheckedRequest checked = check_request(std::move(element));
    if (!checked.request) {
        complete(reply, slot, std::move(checked.error));
        return;
    }
    const RpcRequest& request = *checked.request;
    core_->counters.requests++;
    const Responder responder = make_responder(request, reply, slot);
    try {
        if (request.method == "server.auth") {
            authenticate(request, responder);
            return;
        }
        if (control_only_ && !core_->methods.is_control(request.method))
            throw ApiError::unavailable("unavailable: fibrecelld serves at most " +
                                        std::to_string(core_->config.max_clients) +
                                        " clients at once (api.max_clients); this connection may "
                                        "only call " +
                                        core_->methods.control_names());
        if (!authenticated_)
            throw ApiError::unauthorized(
                "unauthorized: the first call on a TCP connection must be server.auth "
                "{\"token\": ...}");
        if (request.method == "subscribe" || request.method == "unsubscribe") {
            responder.result(change_subscriptions(request, request.method == "subscribe"));
            return;
        }
        const AsyncHandler* handler = core_->methods.find(request.method);
        if (!handler) {
            responder.error(errc::method_not_found, "method not found: " + request.method);
            return;
        }
        const CallContext ctx{request.method, id_, transport_, peer_, user_, request.notification};
        (*handler)(request.params, ctx, responder);
    } catch (const ApiError& e) {
        responder.error(e);
    } catch (const std::exception& e) {
        spdlog::error("api.handler_failed method={} client={} peer={}: {}", request.method, id_,
                      peer_, e.what());
        responder.error(errc::internal_error,
                        "internal error in " + request.method + ": " + e.what());
    }
}

void ClientSession::authenticate(const RpcRequest& request, const Responder& responder) {
    ParamReader p("server.auth", request.params);
    const std::string token =
        transport_ == Transport::tcp ? p.string("token") : p.string_opt("token").value_or("");
    p.finish();
    // After a wrong token nothing on this connection is believed: not the next element of the
    // same batch either, or a batch of guesses would get round one try per connection.
    if (auth_failed_) {
        responder.error(errc::unauthorized,
                        "unauthorized: this connection already gave a wrong token; reconnect");
        return;
    }
    if (transport_ == Transport::tcp && !authenticated_ && !core_->take_auth_attempt()) {
        core_->counters.auth_failures++;
        responder.error(errc::unavailable,
                        "unavailable: more than " +
                            std::to_string(core_->config.tcp.auth_attempts_per_s) +
                            " server.auth attempts a second (api.tcp.auth_attempts_per_s); try "
                            "again shortly");
        close_after_flush();
        return;
    }
    if (transport_ == Transport::tcp && !same_token(token, core_->config.tcp.token)) {
        auth_failed_ = true;
        core_->counters.auth_failures++;
        spdlog::warn("api.auth_failed client={} peer={}", id_, peer_);
        responder.error(errc::unauthorized, "unauthorized: wrong token");
        close_after_flush();  // one try per connection
        return;
    }
    if (!authenticated_) spdlog::info("api.client_authenticated client={} peer={}", id_, peer_);
    authenticated_ = true;
    auth_timer_.cancel();
    responder.result({{"authenticated", true}});
}

bool ClientSession::subscribed(const std::string& topic) const {
    return topics_.contains(topic) || topics_.contains(std::string_view(topic::all));
}

nlohmann::json ClientSession::change_subscriptions(const RpcRequest& request, bool subscribe) {
    ParamReader p(request.method, request.params);
    std::vector<std::string> topics;
    if (p.has("topics")) {
        const auto& list = p.array("topics");
        if (list.empty()) p.fail("topics", "must name at least one topic (or \"*\")");
        for (const auto& t : list) {
            if (!t.is_string() || t.get_ref<const std::string&>().empty() ||
                t.get_ref<const std::string&>().size() > kMaxTopicChars)
                p.fail("topics",
                       "must hold job ids, \"cell\", \"log\" or \"*\" as non-empty strings");
            topics.push_back(t.get<std::string>());
        }
    }
    p.finish();  // absent topics: everything (subscribe) or all of them (unsubscribe)
    if (subscribe) {
        if (topics.empty()) topics.push_back(topic::all);
        if (topics_.size() + topics.size() > kMaxTopicsPerClient)
            throw ApiError::invalid_params(request.method + ": at most " +
                                           std::to_string(kMaxTopicsPerClient) +
                                           " topics per connection");
        for (auto& t : topics) topics_.insert(std::move(t));
    } else {
        if (topics.empty()) topics_.clear();
        for (const auto& t : topics) topics_.erase(t);
        gate_.drop_unless([this](const std::string& t) { return subscribed(t); });
    }
    return {{"topics", nlohmann::json(std::vector<std::string>(topics_.begin(), topics_.end()))}};
}

void ClientSession::deliver(const std::string& topic, const std::string& method, Delivery delivery,
                            const Line& line) {
    if (closing_ || !subscribed(topic)) return;
    if (delivery == Delivery::latest) {
        if (gate_.offer(topic, method, line) == LatestOnlyGate::Outcome::replaced)
            core_->counters.notifications_coalesced++;
        return;
    }
    gate_.flush_topic(topic);  // a held progress line of this topic goes first
    send_notification(line);
}

}  // namespace fibrecell::api
