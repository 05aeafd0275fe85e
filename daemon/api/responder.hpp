#pragma once
// The answer slot of one call, handed to async method handlers. Copyable and thread-safe: any
// copy may complete the call once, from any thread (the answer is posted to the server's
// strand). The first completion wins; later ones are ignored. When the last copy goes away
// unanswered the caller gets -32603 "<method> was dropped without an answer", so a forgotten
// path cannot hang a client.

#include "daemon/api/api_error.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <string>

namespace fibrecell::api {

class Responder {
  public:
    // deliver(response) is called once, with the complete JSON-RPC response object; the server
    // builds Responders, handlers only complete them.
    using Deliver = std::function<void(nlohmann::json response)>;
    Responder(std::string method, nlohmann::json id, Deliver deliver);

    void result(nlohmann::json value) const;
    void error(const ApiError& e) const;
    void error(int code, const std::string& message) const;

    bool done() const;  // completed by some copy
    const std::string& method() const;

  private:
    struct State;
    std::shared_ptr<State> state_;
};

}  // namespace fibrecell::api
