#pragma once
// Comparing a client's token with the configured one in time independent of where the first
// difference is (TCP's server.auth, the dashboard's login).

#include <string>

namespace fibrecell::api {

inline bool same_token(const std::string& given, const std::string& expected) {
    if (expected.empty()) return false;
    unsigned diff = given.size() == expected.size() ? 0u : 1u;
    for (std::size_t i = 0; i < given.size(); ++i)
        diff |= static_cast<unsigned>(static_cast<unsigned char>(given[i]) ^
                                      static_cast<unsigned char>(expected[i % expected.size()]));
    return diff == 0;
}

}  // namespace fibrecell::api
