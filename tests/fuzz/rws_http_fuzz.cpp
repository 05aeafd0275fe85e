// Feeds the bytes as what arrives on an RWS connection: requests (one after another, keep-alive)
// to the simulated IRC5's digest check and routes over an in-memory controller
// (drivers/abb/rws/digest.hpp, rws_routes.hpp); an input starting "HTTP/" as a controller's
// response to the client's readers (digest challenge, status and state JSON). A reply (an error
// status is fine) or Beast rejecting the bytes is the contract; an exception escaping route() or
// a reader, a crash or a sanitizer report is a finding.
#include "drivers/abb/rws/digest.hpp"
#include "drivers/sim/rws/in_memory_controller.hpp"
#include "drivers/abb/rws/rws_json.hpp"
#include "drivers/sim/rws/rws_routes.hpp"

#include <boost/asio/buffer.hpp>
#include <boost/beast/http.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace {

namespace rws = fibrecell::drivers::abb::rws;
namespace sim_rws = fibrecell::drivers::sim::rws;  // the controller's side
namespace beast = boost::beast;
namespace http = beast::http;

// The controller's module data, so that symbol reads and writes meet declared data.
constexpr std::string_view kDataModule =
    "MODULE FcData\n"
    "  PERS num nFcState := 0;\n"
    "  PERS string sFcJobDir := \"HOME:/fibrecell/job\";\n"
    "  VAR robtarget pHome := [[0,0,80],[0,0,1,0],[0,0,-1,1],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
    "  CONST num nLimit := 5;\n"
    "  PROC main()\n"
    "  ENDPROC\n"
    "ENDMODULE\n";

// This client holds mastership, so that every route gets past the check.
class HeldMastership : public sim_rws::MastershipGate {
  public:
    bool held_by_caller() const override { return true; }
    bool held_elsewhere() const override { return false; }
    bool request() override { return true; }
    void release() override {}
};

std::string_view sv(beast::string_view s) {
    return {s.data(), s.size()};
}

// The message at the front of `wire`, consumed; nothing when Beast rejects the bytes.
template <bool isRequest>
std::optional<http::message<isRequest, http::string_body>> next_message(std::string_view& wire) {
    http::parser<isRequest, http::string_body> parser;
    parser.eager(true);
    parser.body_limit(64 * 1024);
    beast::error_code ec;
    while (!parser.is_done()) {
        const std::size_t used = parser.put(boost::asio::buffer(wire.data(), wire.size()), ec);
        wire.remove_prefix(used);
        if (ec == http::error::need_more || (!ec && used == 0)) parser.put_eof(ec);
        if (ec) return std::nullopt;
    }
    return parser.release();
}

void serve_requests(std::string_view wire) {
    sim_rws::InMemoryController controller;
    controller.write_file("FcData.mod", std::string(kDataModule));
    controller.load_module("FcData.mod", false);
    rws::DigestVerifier digest({});
    HeldMastership mastership;
    while (!wire.empty()) {
        const auto req = next_message<true>(wire);
        if (!req) return;
        const std::string method(req->method_string());
        const std::string target(req->target());
        digest.verify(sv((*req)[http::field::authorization]), method, target);
        sim_rws::route({method, target, req->body(), sv((*req)[http::field::host])}, controller,
                   mastership, "T_ROB1");
    }
}

void read_response(std::string_view wire) {
    const auto res = next_message<false>(wire);
    if (!res) return;
    const auto [first, last] = res->equal_range(http::field::www_authenticate);
    for (auto field = first; field != last; ++field) {
        const auto challenge = rws::parse_challenge(sv(field->value()));
        if (!challenge) continue;
        rws::DigestSession session("Default User", "robotics");
        try {
            session.accept(*challenge);
        } catch (const std::invalid_argument&) {
            continue;  // an algorithm or qop the client refuses
        }
        session.authorization("GET", "/rw/rapid/execution?json=1");
    }
    rws::json::parse_status(res->body());
    const auto doc = rws::json::Json::parse(res->body(), nullptr, false);
    if (doc.is_discarded()) return;
    try {
        for (const auto& item : rws::json::state_items(doc))
            for (const char* key : {"value", "ctrlexecstate", "ctrlstate", "row", "name"})
                rws::json::text_field(item, key);
    } catch (const std::runtime_error&) {
        // not a state document
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view wire(reinterpret_cast<const char*>(data), size);
    if (wire.starts_with("HTTP/"))
        read_response(wire);
    else
        serve_requests(wire);
    return 0;
}
