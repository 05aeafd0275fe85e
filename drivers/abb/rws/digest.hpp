#pragma once
// HTTP digest authentication (RFC 2617, RFC 7616) with MD5 and qop=auth, the scheme Robot Web
// Services 1.0 uses on RobotWare 6 (realm "validusers@robapi.abb"). Both sides live here:
//
//   client: parse_challenge() on a 401's WWW-Authenticate, then DigestSession::authorization()
//           for every request; the nonce is reused with nc = 1, 2, 3, ... until the server
//           answers stale=true, when the new challenge replaces it.
//   server: DigestVerifier issues challenges and checks Authorization headers (nonce lifetime,
//           nc replay, stale nonces with valid credentials).
//
// MD5 comes from OpenSSL's libcrypto (EVP). Only the protocol's own hashing lives here; nothing
// in this file touches sockets.

#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::drivers::abb::rws {

// Lower-case hex MD5 of `data` (32 characters).
std::string md5_hex(std::string_view data);

// `n` random bytes from the OpenSSL generator, as 2n lower-case hex characters.
std::string random_hex(std::size_t n);

// The auth-params of one challenge or credentials header, names lower-cased, values unquoted.
using AuthParams = std::map<std::string, std::string>;

// Parses `Digest k=v, k="v", ...` (the scheme is matched case-insensitively). Nothing when the
// header is not a Digest one or is malformed.
std::optional<AuthParams> parse_digest_header(std::string_view header);

// A server's challenge (WWW-Authenticate: Digest ...).
struct DigestChallenge {
    std::string realm;
    std::string nonce;
    std::string opaque;             // echoed back when present
    std::string algorithm = "MD5";  // MD5 or MD5-sess
    std::vector<std::string> qop;   // offered qop values; empty for an RFC 2069 server
    bool stale = false;             // the nonce expired but the credentials were right
};

// Nothing when `header` is not a usable Digest challenge (no nonce/realm, another scheme).
std::optional<DigestChallenge> parse_challenge(std::string_view header);

// Everything the response hash depends on (RFC 2617 section 3.2.2).
struct DigestInput {
    std::string user;
    std::string realm;
    std::string password;
    std::string method;  // "GET", "POST", ...
    std::string uri;     // request-target as sent: path and query
    std::string nonce;
    std::string nc;  // 8 hex digits, "00000001"
    std::string cnonce;
    std::string qop;  // "auth", or empty for the RFC 2069 form
    std::string algorithm = "MD5";
};

// The `response` value: MD5(HA1:nonce:nc:cnonce:qop:HA2), or MD5(HA1:nonce:HA2) without qop;
// HA1 = MD5(user:realm:password) (MD5-sess: MD5(that:nonce:cnonce)), HA2 = MD5(method:uri).
std::string digest_response(const DigestInput& in);

// "00000001" for 1.
std::string format_nc(std::uint32_t nc);

// Client side: holds the current challenge and counts nc. Not thread-safe.
class DigestSession {
  public:
    DigestSession(std::string user, std::string password)
        : user_(std::move(user)), password_(std::move(password)) {}

    // Takes a 401's challenge; resets nc to 0 and draws a new cnonce. Throws std::invalid_argument
    // for an algorithm or qop this client does not support.
    void accept(const DigestChallenge& challenge);
    bool has_challenge() const { return challenge_.has_value(); }
    void forget() { challenge_.reset(); }

    // The Authorization header value for the next request (increments nc).
    std::string authorization(std::string_view method, std::string_view uri);

    const std::string& user() const { return user_; }
    std::uint32_t nc() const { return nc_; }

  private:
    std::string user_;
    std::string password_;
    std::optional<DigestChallenge> challenge_;
    std::string qop_;  // chosen from the challenge's offer
    std::string cnonce_;
    std::uint32_t nc_ = 0;
};

// Server side: issues challenges and verifies credentials. Thread-safe.
class DigestVerifier {
  public:
    struct Config {
        std::string realm = "validusers@robapi.abb";
        std::string user = "Default User";
        std::string password = "robotics";
        std::chrono::seconds nonce_lifetime{300};
    };

    enum class Verdict {
        ok,
        missing,   // no or unparsable Authorization: send a fresh challenge
        stale,     // right credentials, nonce expired or unknown: challenge with stale=true
        rejected,  // wrong user, password, realm, uri or a replayed nc
    };

    struct Result {
        Verdict verdict = Verdict::missing;
        std::string nonce;     // the nonce the client used (ok, stale)
        std::uint32_t nc = 0;  // its nc (ok)
        std::string reason;    // for logs (rejected)
    };

    explicit DigestVerifier(Config config);

    // `authorization` is the header value (may be empty); `method` and `target` of the request.
    Result verify(std::string_view authorization, std::string_view method, std::string_view target);

    struct Challenge {
        std::string nonce;
        std::string header;  // the WWW-Authenticate value
    };
    // A challenge with a new nonce.
    Challenge challenge(bool stale);

    // Makes every nonce issued so far stale (the next use of one gets stale=true).
    void expire_nonces();
    // Forgets every nonce (as after a controller restart).
    void forget_nonces();

    const Config& config() const { return config_; }

  private:
    struct NonceState {
        std::chrono::steady_clock::time_point issued;
        std::uint32_t last_nc = 0;
        bool expired = false;
    };
    Config config_;
    std::string opaque_;
    std::mutex mu_;
    std::map<std::string, NonceState> nonces_;
};

}  // namespace fibrecell::drivers::abb::rws
