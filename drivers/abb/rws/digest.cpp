#include "drivers/abb/rws/digest.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/rand.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <memory>
#include <stdexcept>

namespace fibrecell::drivers::abb::rws {

namespace {

std::string to_hex(const unsigned char* data, std::size_t n) {
    static constexpr char digits[] = "0123456789abcdef";
    std::string out(2 * n, '0');
    for (std::size_t i = 0; i < n; ++i) {
        out[2 * i] = digits[data[i] >> 4];
        out[2 * i + 1] = digits[data[i] & 0xF];
    }
    return out;
}

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool iequals(std::string_view a, std::string_view b) {
    return lower(a) == lower(b);
}

bool is_space(char c) {
    return c == ' ' || c == '\t';
}

// RFC 7235 token characters.
bool is_token_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 ||
           std::string_view("!#$%&'*+-.^_`|~").find(c) != std::string_view::npos;
}

std::string quote(std::string_view s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out.push_back('\\');
        out.push_back(c);
    }
    out.push_back('"');
    return out;
}

std::vector<std::string> split_list(std::string_view s) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : s) {
        if (c == ',') {
            if (!cur.empty()) out.push_back(lower(cur));
            cur.clear();
        } else if (!is_space(c)) {
            cur.push_back(c);
        }
    }
    if (!cur.empty()) out.push_back(lower(cur));
    return out;
}

}  // namespace

std::string md5_hex(std::string_view data) {
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
    std::array<unsigned char, EVP_MAX_MD_SIZE> md{};
    unsigned int len = 0;
    if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_md5(), nullptr) != 1 ||
        EVP_DigestUpdate(ctx.get(), data.data(), data.size()) != 1 ||
        EVP_DigestFinal_ex(ctx.get(), md.data(), &len) != 1)
        throw std::runtime_error("OpenSSL MD5 is not available");
    return to_hex(md.data(), len);
}

std::string random_hex(std::size_t n) {
    std::vector<unsigned char> bytes(n);
    if (RAND_bytes(bytes.data(), static_cast<int>(n)) != 1)
        throw std::runtime_error("OpenSSL random generator failed");
    return to_hex(bytes.data(), n);
}

std::optional<AuthParams> parse_digest_header(std::string_view h) {
    std::size_t i = 0;
    while (i < h.size() && is_space(h[i])) ++i;
    const std::size_t scheme_start = i;
    while (i < h.size() && is_token_char(h[i])) ++i;
    if (!iequals(h.substr(scheme_start, i - scheme_start), "digest")) return std::nullopt;

    AuthParams params;
    while (i < h.size()) {
        while (i < h.size() && (is_space(h[i]) || h[i] == ',')) ++i;
        if (i >= h.size()) break;
        const std::size_t name_start = i;
        while (i < h.size() && is_token_char(h[i])) ++i;
        const std::string name = lower(h.substr(name_start, i - name_start));
        while (i < h.size() && is_space(h[i])) ++i;
        if (name.empty() || i >= h.size() || h[i] != '=') return std::nullopt;
        ++i;
        while (i < h.size() && is_space(h[i])) ++i;
        std::string value;
        if (i < h.size() && h[i] == '"') {
            ++i;
            bool closed = false;
            while (i < h.size()) {
                const char c = h[i++];
                if (c == '\\' && i < h.size()) {
                    value.push_back(h[i++]);
                } else if (c == '"') {
                    closed = true;
                    break;
                } else {
                    value.push_back(c);
                }
            }
            if (!closed) return std::nullopt;
        } else {
            const std::size_t v = i;
            while (i < h.size() && is_token_char(h[i])) ++i;
            value = std::string(h.substr(v, i - v));
        }
        params[name] = std::move(value);
        while (i < h.size() && is_space(h[i])) ++i;
        if (i < h.size() && h[i] != ',') return std::nullopt;
    }
    return params;
}

std::optional<DigestChallenge> parse_challenge(std::string_view header) {
    const auto params = parse_digest_header(header);
    if (!params) return std::nullopt;
    DigestChallenge c;
    const auto get = [&](const char* k) {
        const auto it = params->find(k);
        return it == params->end() ? std::string() : it->second;
    };
    c.realm = get("realm");
    c.nonce = get("nonce");
    if (c.nonce.empty() || !params->count("realm")) return std::nullopt;
    c.opaque = get("opaque");
    if (params->count("algorithm")) c.algorithm = get("algorithm");
    c.qop = split_list(get("qop"));
    c.stale = iequals(get("stale"), "true");
    return c;
}

std::string format_nc(std::uint32_t nc) {
    std::array<char, 9> buf{};
    std::snprintf(buf.data(), buf.size(), "%08x", nc);
    return buf.data();
}

std::string digest_response(const DigestInput& in) {
    std::string ha1 = md5_hex(in.user + ":" + in.realm + ":" + in.password);
    if (iequals(in.algorithm, "MD5-sess")) ha1 = md5_hex(ha1 + ":" + in.nonce + ":" + in.cnonce);
    const std::string ha2 = md5_hex(in.method + ":" + in.uri);
    if (in.qop.empty()) return md5_hex(ha1 + ":" + in.nonce + ":" + ha2);
    return md5_hex(ha1 + ":" + in.nonce + ":" + in.nc + ":" + in.cnonce + ":" + in.qop + ":" + ha2);
}

// ---- Client ------------------------------------------------------------------------------------

void DigestSession::accept(const DigestChallenge& challenge) {
    if (!iequals(challenge.algorithm, "MD5") && !iequals(challenge.algorithm, "MD5-sess"))
        throw std::invalid_argument("the server asks for digest algorithm " + challenge.algorithm +
                                    "; only MD5 and MD5-sess are supported");
    std::string qop;
    if (!challenge.qop.empty()) {
        if (std::find(challenge.qop.begin(), challenge.qop.end(), "auth") == challenge.qop.end())
            throw std::invalid_argument("the server offers no digest qop=auth");
        qop = "auth";
    }
    challenge_ = challenge;
    qop_ = qop;
    cnonce_ = random_hex(8);
    nc_ = 0;
}

std::string DigestSession::authorization(std::string_view method, std::string_view uri) {
    if (!challenge_) throw std::logic_error("DigestSession::authorization without a challenge");
    ++nc_;
    DigestInput in;
    in.user = user_;
    in.realm = challenge_->realm;
    in.password = password_;
    in.method = std::string(method);
    in.uri = std::string(uri);
    in.nonce = challenge_->nonce;
    in.nc = format_nc(nc_);
    in.cnonce = cnonce_;
    in.qop = qop_;
    in.algorithm = challenge_->algorithm;

    std::string h = "Digest username=" + quote(user_) + ", realm=" + quote(in.realm) +
                    ", nonce=" + quote(in.nonce) + ", uri=" + quote(in.uri) +
                    ", algorithm=" + challenge_->algorithm;
    if (!qop_.empty()) h += ", qop=" + qop_ + ", nc=" + in.nc + ", cnonce=" + quote(cnonce_);
    h += ", response=" + quote(digest_response(in));
    if (!challenge_->opaque.empty()) h += ", opaque=" + quote(challenge_->opaque);
    return h;
}

// ---- Server ------------------------------------------------------------------------------------

DigestVerifier::DigestVerifier(Config config)
    : config_(std::move(config)), opaque_(random_hex(16)) {}

DigestVerifier::Challenge DigestVerifier::challenge(bool stale) {
    const std::string nonce = random_hex(16);
    const auto now = std::chrono::steady_clock::now();
    {
        std::lock_guard lock(mu_);
        // Drop nonces long past their lifetime so that the table stays small.
        for (auto it = nonces_.begin(); it != nonces_.end();) {
            if (now - it->second.issued > 2 * config_.nonce_lifetime)
                it = nonces_.erase(it);
            else
                ++it;
        }
        nonces_[nonce] = NonceState{now, 0, false};
    }
    return {nonce, "Digest realm=" + quote(config_.realm) + ", domain=\"/\", qop=\"auth\", nonce=" +
                       quote(nonce) + ", opaque=" + quote(opaque_) +
                       ", algorithm=MD5, stale=" + (stale ? "TRUE" : "FALSE")};
}

DigestVerifier::Result DigestVerifier::verify(std::string_view authorization,
                                              std::string_view method, std::string_view target) {
    Result r;
    const auto p = parse_digest_header(authorization);
    if (!p) return r;  // missing
    const auto get = [&](const char* k) {
        const auto it = p->find(k);
        return it == p->end() ? std::string() : it->second;
    };
    r.nonce = get("nonce");
    if (r.nonce.empty() || get("response").empty()) return r;
    r.verdict = Verdict::rejected;
    if (get("username") != config_.user) {
        r.reason = "unknown user '" + get("username") + "'";
        return r;
    }
    if (get("realm") != config_.realm) {
        r.reason = "wrong realm";
        return r;
    }
    if (get("uri") != target) {
        r.reason = "digest uri does not match the request target";
        return r;
    }
    std::string algorithm = p->count("algorithm") ? get("algorithm") : "MD5";
    if (!iequals(algorithm, "MD5")) {
        r.reason = "unsupported algorithm " + algorithm;
        return r;
    }
    DigestInput in;
    in.user = config_.user;
    in.realm = config_.realm;
    in.password = config_.password;
    in.method = std::string(method);
    in.uri = std::string(target);
    in.nonce = r.nonce;
    in.qop = get("qop");
    in.nc = get("nc");
    in.cnonce = get("cnonce");
    if (in.qop != "auth") {
        r.reason = "qop must be auth";
        return r;
    }
    std::uint32_t nc = 0;
    try {
        std::size_t used = 0;
        const unsigned long v = std::stoul(in.nc, &used, 16);
        if (used != in.nc.size() || in.nc.size() != 8) throw std::invalid_argument("nc");
        nc = static_cast<std::uint32_t>(v);
    } catch (const std::exception&) {
        r.reason = "malformed nc";
        return r;
    }
    const std::string expected = digest_response(in);
    const std::string given = lower(get("response"));
    if (given.size() != expected.size() ||
        CRYPTO_memcmp(given.data(), expected.data(), expected.size()) != 0) {
        r.reason = "wrong password or response";
        return r;
    }
    // The credentials are right; now the nonce.
    std::lock_guard lock(mu_);
    const auto it = nonces_.find(r.nonce);
    const auto now = std::chrono::steady_clock::now();
    if (it == nonces_.end() || it->second.expired ||
        now - it->second.issued > config_.nonce_lifetime) {
        r.verdict = Verdict::stale;
        return r;
    }
    if (nc <= it->second.last_nc) {
        r.reason = "replayed nc " + in.nc;
        return r;
    }
    it->second.last_nc = nc;
    r.nc = nc;
    r.verdict = Verdict::ok;
    return r;
}

void DigestVerifier::expire_nonces() {
    std::lock_guard lock(mu_);
    for (auto& [nonce, state] : nonces_) state.expired = true;
}

void DigestVerifier::forget_nonces() {
    std::lock_guard lock(mu_);
    nonces_.clear();
}

}  // namespace fibrecell::drivers::abb::rws
