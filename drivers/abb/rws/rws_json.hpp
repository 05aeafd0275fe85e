#pragma once
// Internal (client and server .cpp files only): the JSON representation RWS 1.0 returns for
// `?json=1`. A resource is a list of typed items under `_embedded._state`:
//
//   {"_links": {"base": {"href": "http://host/rw/rapid/"}},
//    "_embedded": {"_state": [{"_type": "rap-execution", "_title": "execution",
//                              "ctrlexecstate": "stopped", "cycle": "once"}]}}
//
// Values are strings on the wire (numbers too). Errors carry a controller return code and a
// message: {"status": {"code": -1073445865, "msg": "..."}} (readers also accept it under
// `_embedded`, and the XHTML form <span class="msg">...</span>).

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <string_view>

namespace fibrecell::drivers::abb::rws::json {

using Json = nlohmann::json;

// One item: {"_type": type, "_title": title, fields...}.
Json item(std::string_view type, std::string_view title);

// The whole document around `items` (an array).
Json state_document(std::string_view base_href, Json items);

// The `_embedded._state` array of a document; throws std::runtime_error when absent.
const Json& state_items(const Json& document);

// A field as text whether it came as a string or a number; nothing when absent.
std::optional<std::string> text_field(const Json& item, std::string_view key);

struct Status {
    long long code = 0;
    std::string msg;
};

Json status_document(long long code, std::string_view msg);

// A document as the body sent. Messages echo request bytes (a target, a Host header, a module
// path), which need not be UTF-8: such bytes become U+FFFD instead of making the dump throw.
std::string wire_text(const Json& document);

// The status of an error body (JSON or XHTML); nothing when there is none.
std::optional<Status> parse_status(std::string_view body);

}  // namespace fibrecell::drivers::abb::rws::json
