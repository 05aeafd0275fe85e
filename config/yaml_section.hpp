#pragma once
// Strict, typed reading of YAML configuration. Every module reads its own section into a typed
// struct through a Section: values are checked at load time, unknown keys are rejected, and every
// error names the file, the line and the full key path ("planner.mu").

#include <yaml-cpp/yaml.h>

#include <array>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::config {

class ConfigError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class Section {
  public:
    // Parses a whole file; throws ConfigError naming the file on syntax errors.
    static Section load_file(const std::string& path);
    // Parses YAML text; `origin` names it in messages (a file name or "<job.submit>").
    static Section load_text(const std::string& text, const std::string& origin);

    Section(YAML::Node node, std::string path, std::shared_ptr<const std::string> origin);

    bool has(std::string_view key) const;

    // Required scalar / sequence of T (int, double, bool, std::string, std::vector<...>).
    template <class T>
    T get(std::string_view key);
    // Optional value with a default.
    template <class T>
    T get_or(std::string_view key, T fallback);

    // A number checked against [min, max] (or (min, max] when min_exclusive).
    double number(std::string_view key, double fallback, double min, double max,
                  bool min_exclusive = false);
    int integer(std::string_view key, int fallback, int min, int max);
    std::array<double, 3> vec3(std::string_view key);
    std::array<double, 3> vec3_or(std::string_view key, std::array<double, 3> fallback);
    // An absolute file system path; a leading "~/" is the home directory of the user the
    // service runs as ($HOME), so a shipped config can name a private directory.
    std::string path_or(std::string_view key, std::string fallback);
    // One of the allowed words.
    std::string choice(std::string_view key, std::string fallback,
                       const std::vector<std::string>& allowed);

    // A nested mapping; an absent key gives an empty section (all defaults).
    Section section(std::string_view key);
    // A sequence of mappings.
    std::vector<Section> sections(std::string_view key);
    // The raw node for shapes a helper does not cover; marks the key as read.
    YAML::Node node(std::string_view key);
    // Keys of this mapping, in file order (for maps whose keys are names, such as `regions`).
    std::vector<std::string> keys() const;

    // Rejects keys that were never read: call after reading everything a section supports.
    void finish() const;

    [[noreturn]] void fail(std::string_view key, const std::string& problem) const;
    [[noreturn]] void fail_here(const std::string& problem) const;

    const std::string& path() const { return path_; }
    std::string key_path(std::string_view key) const;
    const std::string& origin() const { return *origin_; }
    bool is_null() const { return !node_ || node_.IsNull(); }

  private:
    YAML::Node child(std::string_view key, bool required);
    std::string where(const YAML::Node& n) const;

    YAML::Node node_;
    std::string path_;  // "" at the root, "planner", "model.load_case", "regions.left_pin"
    std::shared_ptr<const std::string> origin_;
    std::set<std::string, std::less<>> read_;
};

}  // namespace fibrecell::config
