#include "config/yaml_section.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

namespace fibrecell::config {
namespace {

std::string describe_value(const YAML::Node& n) {
    if (n.IsScalar()) return "'" + n.Scalar() + "'";
    if (n.IsSequence()) return "a list";
    if (n.IsMap()) return "a mapping";
    return "nothing";
}

template <class T>
const char* type_name() {
    if constexpr (std::is_same_v<T, bool>) return "true or false";
    if constexpr (std::is_same_v<T, int>) return "a whole number";
    if constexpr (std::is_same_v<T, double>) return "a number";
    if constexpr (std::is_same_v<T, std::string>) return "a string";
    if constexpr (std::is_same_v<T, std::vector<int>>) return "a list of whole numbers";
    if constexpr (std::is_same_v<T, std::vector<double>>) return "a list of numbers";
    if constexpr (std::is_same_v<T, std::vector<std::string>>) return "a list of strings";
    return "a value of another type";
}

template <class T>
struct ListOf {
    static constexpr bool is_list = false;
};
template <class E>
struct ListOf<std::vector<E>> {
    static constexpr bool is_list = true;
    using element = E;
};

// No configuration or job comes near this many values; a document that does is aliases
// expanding (a "billion laughs"), refused before anything walks it.
constexpr std::size_t kMaxValues = 100'000;

// YAML allows a key once per mapping; yaml-cpp keeps every pair and its lookups find the first,
// so a repeated key would silently lose the value written last. Refused, with both lines.
void refuse_duplicate_keys(const YAML::Node& node, const std::string& path, const std::string& origin,
                           std::size_t& values) {
    if (++values > kMaxValues)
        throw ConfigError(origin + ": more than " + std::to_string(kMaxValues) +
                          " values (aliases that expand?)");
    if (node.IsSequence()) {
        for (std::size_t i = 0; i < node.size(); ++i)
            refuse_duplicate_keys(node[i], path + "[" + std::to_string(i) + "]", origin, values);
        return;
    }
    if (!node.IsMap()) return;
    std::map<std::string, int> first_line;
    for (const auto& kv : node) {
        const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string();
        const std::string key_path = path.empty() ? key : path + "." + key;
        const int line = kv.first.Mark().line + 1;
        if (kv.first.IsScalar()) {
            const auto [it, fresh] = first_line.emplace(key, line);
            if (!fresh)
                throw ConfigError(origin + ": line " + std::to_string(line) + ": " + key_path +
                                  ": the key appears twice in one mapping (first at line " +
                                  std::to_string(it->second) + ")");
        }
        refuse_duplicate_keys(kv.second, key_path, origin, values);
    }
}

}  // namespace

Section Section::load_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw ConfigError(path + ": cannot open file");
    std::stringstream text;
    text << in.rdbuf();
    return load_text(text.str(), path);
}

Section Section::load_text(const std::string& text, const std::string& origin) {
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        throw ConfigError(origin + ": line " + std::to_string(e.mark.line + 1) +
                          ": YAML syntax error: " + e.msg);
    }
    if (root && !root.IsNull() && !root.IsMap())
        throw ConfigError(origin + ": the document must be a mapping of keys to values");
    std::size_t values = 0;
    refuse_duplicate_keys(root, "", origin, values);
    return Section(root, "", std::make_shared<const std::string>(origin));
}

Section::Section(YAML::Node node, std::string path, std::shared_ptr<const std::string> origin)
    : node_(std::move(node)), path_(std::move(path)), origin_(std::move(origin)) {
    if (node_ && !node_.IsNull() && !node_.IsMap())
        fail_here("must be a mapping of keys to values, not " + describe_value(node_));
    if (node_ && node_.IsMap())
        for (const auto& kv : node_)
            if (!kv.first.IsScalar())
                throw ConfigError(where(kv.first) + ": " + (path_.empty() ? "document" : path_) +
                                  ": a key must be a plain name, not " + describe_value(kv.first));
}

bool Section::has(std::string_view key) const {
    return node_ && node_.IsMap() && node_[std::string(key)] && !node_[std::string(key)].IsNull();
}

std::string Section::key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::string Section::where(const YAML::Node& n) const {
    std::string w = *origin_;
    if (n && n.Mark().line >= 0) w += ": line " + std::to_string(n.Mark().line + 1);
    return w;
}

void Section::fail(std::string_view key, const std::string& problem) const {
    YAML::Node n = has(key) ? node_[std::string(key)] : node_;
    throw ConfigError(where(n) + ": " + key_path(key) + ": " + problem);
}

void Section::fail_here(const std::string& problem) const {
    throw ConfigError(where(node_) + ": " + (path_.empty() ? "document" : path_) + ": " + problem);
}

YAML::Node Section::child(std::string_view key, bool required) {
    read_.emplace(key);
    if (!has(key)) {
        if (required) fail(key, "is required");
        return YAML::Node();
    }
    return node_[std::string(key)];
}

template <class T>
T Section::get(std::string_view key) {
    YAML::Node n = child(key, true);
    if constexpr (ListOf<T>::is_list) {
        // Element by element, so a bad one is named by its place: "ccf_after_pla[2]".
        using E = typename ListOf<T>::element;
        if (!n.IsSequence())
            fail(key, std::string("must be ") + type_name<T>() + ", not " + describe_value(n));
        T values;
        for (std::size_t i = 0; i < n.size(); ++i) {
            const YAML::Node e = n[i];
            const std::string at = std::string(key) + "[" + std::to_string(i) + "]";
            try {
                if (!e.IsScalar()) throw YAML::BadConversion(e.Mark());
                values.push_back(e.as<E>());
            } catch (const YAML::Exception&) {
                throw ConfigError(where(e) + ": " + key_path(at) + ": must be " + type_name<E>() +
                                  ", not " + describe_value(e));
            }
            if constexpr (std::is_same_v<E, double>) {
                if (!std::isfinite(values.back()))
                    throw ConfigError(where(e) + ": " + key_path(at) + ": must be a finite number");
            }
        }
        return values;
    } else {
        try {
            if (!n.IsScalar()) throw YAML::BadConversion(n.Mark());
            T value = n.as<T>();
            if constexpr (std::is_same_v<T, double>) {
                if (!std::isfinite(value)) fail(key, "must be a finite number");
            }
            return value;
        } catch (const YAML::Exception&) {
            fail(key, std::string("must be ") + type_name<T>() + ", not " + describe_value(n));
        }
    }
}

template <class T>
T Section::get_or(std::string_view key, T fallback) {
    if (!has(key)) {
        read_.emplace(key);
        return fallback;
    }
    return get<T>(key);
}

template bool Section::get<bool>(std::string_view);
template int Section::get<int>(std::string_view);
template double Section::get<double>(std::string_view);
template std::string Section::get<std::string>(std::string_view);
template std::vector<int> Section::get<std::vector<int>>(std::string_view);
template std::vector<double> Section::get<std::vector<double>>(std::string_view);
template std::vector<std::string> Section::get<std::vector<std::string>>(std::string_view);
template bool Section::get_or<bool>(std::string_view, bool);
template int Section::get_or<int>(std::string_view, int);
template double Section::get_or<double>(std::string_view, double);
template std::string Section::get_or<std::string>(std::string_view, std::string);
template std::vector<int> Section::get_or<std::vector<int>>(std::string_view, std::vector<int>);
template std::vector<double> Section::get_or<std::vector<double>>(std::string_view,
                                                                  std::vector<double>);
template std::vector<std::string> Section::get_or<std::vector<std::string>>(
    std::string_view, std::vector<std::string>);

double Section::number(std::string_view key, double fallback, double min, double max,
                       bool min_exclusive) {
    const double v = get_or<double>(key, fallback);
    const bool low = min_exclusive ? v <= min : v < min;
    if (low || v > max) {
        std::ostringstream msg;
        msg << "must be in " << (min_exclusive ? "(" : "[") << min << ", " << max << "], got " << v;
        fail(key, msg.str());
    }
    return v;
}

int Section::integer(std::string_view key, int fallback, int min, int max) {
    const int v = get_or<int>(key, fallback);
    if (v < min || v > max)
        fail(key, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                      std::to_string(v));
    return v;
}

std::array<double, 3> Section::vec3(std::string_view key) {
    const auto v = get<std::vector<double>>(key);
    if (v.size() != 3) fail(key, "must be a list of 3 numbers [x, y, z]");
    for (double c : v)
        if (!std::isfinite(c)) fail(key, "must hold finite numbers");
    return {v[0], v[1], v[2]};
}

std::array<double, 3> Section::vec3_or(std::string_view key, std::array<double, 3> fallback) {
    if (!has(key)) {
        read_.emplace(key);
        return fallback;
    }
    return vec3(key);
}

std::string Section::path_or(std::string_view key, std::string fallback) {
    std::string p = get_or<std::string>(key, std::move(fallback));
    if (p == "~" || p.starts_with("~/")) {
        const char* home = std::getenv("HOME");
        if (home == nullptr || home[0] != '/')
            fail(key, "starts with ~, but HOME is not set to an absolute path");
        p = std::string(home) + p.substr(1);
    }
    if (p.empty() || p.front() != '/')
        fail(key, "must be an absolute path (or start with ~/), got '" + p + "'");
    return p;
}

std::string Section::choice(std::string_view key, std::string fallback,
                            const std::vector<std::string>& allowed) {
    std::string v = get_or<std::string>(key, std::move(fallback));
    for (const auto& a : allowed)
        if (a == v) return v;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail(key, "must be one of " + list + ", got '" + v + "'");
}

Section Section::section(std::string_view key) {
    return Section(child(key, false), key_path(key), origin_);
}

std::vector<Section> Section::sections(std::string_view key) {
    YAML::Node n = child(key, false);
    std::vector<Section> out;
    if (!n) return out;
    if (!n.IsSequence()) fail(key, "must be a list");
    for (std::size_t i = 0; i < n.size(); ++i)
        out.emplace_back(n[i], key_path(key) + "[" + std::to_string(i) + "]", origin_);
    return out;
}

YAML::Node Section::node(std::string_view key) {
    return child(key, false);
}

std::vector<std::string> Section::keys() const {
    std::vector<std::string> out;
    if (!node_ || !node_.IsMap()) return out;
    for (const auto& kv : node_) out.push_back(kv.first.as<std::string>());
    return out;
}

void Section::finish() const {
    if (!node_ || !node_.IsMap()) return;
    for (const auto& kv : node_) {
        const std::string k = kv.first.as<std::string>();
        if (!read_.contains(k))
            throw ConfigError(where(kv.first) + ": " + key_path(k) + ": unknown key");
    }
}

}  // namespace fibrecell::config
