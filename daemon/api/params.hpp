#pragma once
// Typed reading of a call's named params for method handlers: every problem becomes an
// invalid_params ApiError (-32602) that names the method and the member, e.g.
//   "job.get: params.job is required (a string)".
//
//   ParamReader p(ctx.method, params);
//   const std::string job = p.string("job");
//   const bool start = p.boolean_or("start", false);
//   p.finish();  // rejects members the method does not know

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>

namespace fibrecell::api {

class ParamReader {
  public:
    // params: the call's params (an object; an absent params arrives as {}).
    ParamReader(std::string method, const nlohmann::json& params);

    bool has(std::string_view key) const;  // present, null too (which every reader refuses)
    std::string string(std::string_view key);
    std::optional<std::string> string_opt(std::string_view key);
    bool boolean_or(std::string_view key, bool fallback);
    std::int64_t integer_or(std::string_view key, std::int64_t fallback, std::int64_t min,
                            std::int64_t max);
    double number_or(std::string_view key, double fallback, double min, double max);
    const nlohmann::json& object(std::string_view key);  // a required JSON object
    const nlohmann::json& array(std::string_view key);   // a required JSON array

    // Rejects members that were never read.
    void finish() const;

    [[noreturn]] void fail(std::string_view key, const std::string& problem) const;

  private:
    const nlohmann::json* member(std::string_view key, bool required, const char* kind);

    std::string method_;
    const nlohmann::json& params_;
    std::set<std::string, std::less<>> read_;
};

}  // namespace fibrecell::api
