#pragma once
// Base64 (RFC 4648, standard alphabet, padded) for job files carried inline in job.submit.

#include <stdexcept>
#include <string>
#include <string_view>

namespace fibrecell::config {

std::string base64_encode(std::string_view bytes);
// Throws std::invalid_argument naming the offset of the first character that is not base64 or
// when the length or padding is wrong. Whitespace is not accepted.
std::string base64_decode(std::string_view text);

}  // namespace fibrecell::config
