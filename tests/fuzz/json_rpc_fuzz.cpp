// Feeds the bytes as newline-delimited JSON-RPC lines through the socket API's framing and checks
// (daemon/api/json_rpc.hpp: parse_line, check_request, the answers), as ClientSession::handle_line
// takes a line apart. An answer for every line is the contract; any exception, crash or sanitizer
// report is a finding (in the service it escapes the connection's handler and ends fibrecelld).
#include "daemon/api/json_rpc.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace {

namespace api = fibrecell::api;
using nlohmann::json;

// The answer to one request object: its error, or a result that echoes the params.
json answer(json&& element) {
    api::CheckedRequest checked = api::check_request(std::move(element));
    if (!checked.request) return std::move(checked.error);
    return api::result_response(checked.request->id, std::move(checked.request->params));
}

void handle_line(std::string_view line) {
    if (line.find_first_not_of(" \t") == std::string_view::npos) return;
    api::ParsedLine parsed = api::parse_line(line);
    if (!parsed.error.is_null()) {
        api::to_line(parsed.error);
        return;
    }
    json message = std::move(parsed.message);
    if (!message.is_array()) {
        api::to_line(answer(std::move(message)));
        return;
    }
    json answers = json::array();
    for (auto& element : message) answers.push_back(answer(std::move(element)));
    api::to_line(answers);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    while (!rest.empty()) {
        const auto nl = rest.find('\n');
        std::string_view line = rest.substr(0, nl);
        rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        handle_line(line);
    }
    return 0;
}
