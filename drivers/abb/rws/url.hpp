#pragma once
// Percent-encoding for request targets and application/x-www-form-urlencoded bodies, and the
// decoding the server needs. RWS paths carry '$' literally ("/fileservice/$HOME/x.mod").

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fibrecell::drivers::abb::rws {

using FormFields = std::vector<std::pair<std::string, std::string>>;

// Keeps unreserved characters and `keep`; every other byte becomes %XX.
std::string percent_encode(std::string_view text, std::string_view keep = {});

// %XX decoded; '+' becomes a space when `plus_is_space` (form bodies and query strings).
// Malformed escapes are kept as written.
std::string percent_decode(std::string_view text, bool plus_is_space);

// "a=1&b=x%20y" (keeps "$/:,[]" readable, as RWS clients send module paths and RAPID values).
std::string form_encode(const FormFields& fields);

// The fields of a form body or query string, decoded, in order.
FormFields parse_form(std::string_view text);

// The first value of `name`, or `fallback`.
std::string form_value(const FormFields& fields, std::string_view name,
                       std::string_view fallback = {});

}  // namespace fibrecell::drivers::abb::rws
