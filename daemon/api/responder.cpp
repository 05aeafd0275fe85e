#include "daemon/api/responder.hpp"

#include "daemon/api/json_rpc.hpp"

#include <atomic>

namespace fibrecell::api {

struct Responder::State {
    std::string method;
    nlohmann::json id;
    Deliver deliver;
    std::atomic<bool> done{false};

    void complete(nlohmann::json response) {
        if (done.exchange(true)) return;
        deliver(std::move(response));
    }
    ~State() {
        if (done.load()) return;
        try {
            complete(
                error_response(id, errc::internal_error,
                               "internal error: " + method + " was dropped without an answer"));
        } catch (...) {
            // A destructor must not throw; the connection is probably gone anyway.
        }
    }
};

Responder::Responder(std::string method, nlohmann::json id, Deliver deliver)
    : state_(std::make_shared<State>()) {
    state_->method = std::move(method);
    state_->id = std::move(id);
    state_->deliver = std::move(deliver);
}

void Responder::result(nlohmann::json value) const {
    state_->complete(result_response(state_->id, std::move(value)));
}

void Responder::error(const ApiError& e) const {
    state_->complete(error_response(state_->id, e.code(), e.what(), e.data()));
}

void Responder::error(int code, const std::string& message) const {
    state_->complete(error_response(state_->id, code, message));
}

bool Responder::done() const {
    return state_->done.load();
}

const std::string& Responder::method() const {
    return state_->method;
}

}  // namespace fibrecell::api
