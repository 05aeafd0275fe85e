#include "planner/plan/toolpaths_json.hpp"


#include "planner/input_error.hpp"
#include "planner/io/file_text.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

// 1e-4 mm is far below any bead width; the shortest round-trip form keeps "12.5" short.
void append_number(std::string& out, double value) {
    if (!std::isfinite(value))
        throw std::invalid_argument("toolpaths.json: non-finite coordinate or height");
    double rounded = std::round(value * 1e4) / 1e4;
    if (rounded == 0) rounded = 0;  // no "-0"
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, rounded);
    out.append(buffer, result.ptr);
}

void append_path(std::string& out, const Toolpath& path) {
    out += R"({"role": ")";
    out += to_string(path.role);
    out += R"(", "closed": )";
    out += path.closed ? "true" : "false";
    out += R"(, "points": [)";
    for (std::size_t i = 0; i < path.points.size(); ++i) {
        out += i == 0 ? "[" : ", [";
        append_number(out, path.points[i].x());
        out += ", ";
        append_number(out, path.points[i].y());
        out += "]";
    }
    out += "]}";
}

// Error context: "layers[2].paths[5]".
std::string at(const std::string& where, const char* key) {
    return where.empty() ? std::string(key) : where + "." + key;
}

const nlohmann::json& member(const std::string& file, const nlohmann::json& object,
                             const std::string& where, const char* key) {
    if (!object.is_object()) throw InputError(file, where, "expected an object");
    const auto it = object.find(key);
    if (it == object.end()) throw InputError(file, at(where, key), "missing");
    return *it;
}

double number(const std::string& file, const nlohmann::json& value, const std::string& where) {
    if (!value.is_number()) throw InputError(file, where, "expected a number");
    const double x = value.get<double>();
    if (!std::isfinite(x)) throw InputError(file, where, "not finite");
    return x;
}

const nlohmann::json& array(const std::string& file, const nlohmann::json& value,
                            const std::string& where) {
    if (!value.is_array()) throw InputError(file, where, "expected an array");
    return value;
}

PathRole parse_role(const std::string& file, const nlohmann::json& value,
                    const std::string& where) {
    if (value.is_string()) {
        const std::string& name = value.get_ref<const std::string&>();
        for (PathRole role :
             {PathRole::perimeter, PathRole::infill, PathRole::fibre, PathRole::fibre_boundary})
            if (name == to_string(role)) return role;
        throw InputError(file, where, "unknown role '" + name + "'");
    }
    throw InputError(file, where, "expected a role name");
}

Head parse_head(const std::string& file, const nlohmann::json& value, const std::string& where) {
    if (value == "pla") return Head::pla;
    if (value == "ccf") return Head::ccf;
    throw InputError(file, where, "expected \"pla\" or \"ccf\"");
}

Toolpath parse_path(const std::string& file, const nlohmann::json& json, const std::string& where) {
    Toolpath path;
    path.role = parse_role(file, member(file, json, where, "role"), at(where, "role"));
    const nlohmann::json& closed = member(file, json, where, "closed");
    if (!closed.is_boolean()) throw InputError(file, at(where, "closed"), "expected true or false");
    path.closed = closed.get<bool>();
    const std::string points_at = at(where, "points");
    const nlohmann::json& points = array(file, member(file, json, where, "points"), points_at);
    path.points.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::string point_at = points_at + "[" + std::to_string(i) + "]";
        if (!points[i].is_array() || points[i].size() != 2)
            throw InputError(file, point_at, "expected [x, y]");
        path.points.emplace_back(number(file, points[i][0], point_at),
                                 number(file, points[i][1], point_at));
    }
    return path;
}

ToolpathLayer parse_layer(const std::string& file, const nlohmann::json& json,
                          const std::string& where) {
    ToolpathLayer layer;
    const nlohmann::json& index = member(file, json, where, "index");
    if (!index.is_number_integer())
        throw InputError(file, at(where, "index"), "expected an integer");
    layer.index = index.get<int>();
    layer.z = number(file, member(file, json, where, "z"), at(where, "z"));
    layer.head = parse_head(file, member(file, json, where, "head"), at(where, "head"));
    layer.thickness = number(file, member(file, json, where, "thickness"), at(where, "thickness"));
    const std::string paths_at = at(where, "paths");
    const nlohmann::json& paths = array(file, member(file, json, where, "paths"), paths_at);
    layer.paths.reserve(paths.size());
    for (std::size_t i = 0; i < paths.size(); ++i)
        layer.paths.push_back(parse_path(file, paths[i], paths_at + "[" + std::to_string(i) + "]"));
    return layer;
}

}  // namespace

std::string toolpaths_json_text(std::string_view strategy,
                                const std::vector<ToolpathLayer>& layers) {
    std::string out = R"({"format": ")" + std::string(toolpaths_format) +
                      R"(", "units": "mm", "strategy": )" + nlohmann::json(strategy).dump() +
                      ",\n \"layers\": [";
    for (std::size_t l = 0; l < layers.size(); ++l) {
        const ToolpathLayer& layer = layers[l];
        out += l == 0 ? "\n  " : ",\n  ";
        out += R"({"index": )" + std::to_string(layer.index) + R"(, "z": )";
        append_number(out, layer.z);
        out += R"(, "head": ")";
        out += to_string(layer.head);
        out += R"(", "thickness": )";
        append_number(out, layer.thickness);
        out += R"(, "paths": [)";
        for (std::size_t p = 0; p < layer.paths.size(); ++p) {
            out += p == 0 ? "\n   " : ",\n   ";
            append_path(out, layer.paths[p]);
        }
        out += "]}";
    }
    out += "]}\n";
    return out;
}

ToolpathsFile read_toolpaths_json(const std::string& path) {
    nlohmann::json json;
    try {
        json = nlohmann::json::parse(read_file_text(path));
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(path, "", std::string("not valid JSON: ") + e.what());
    }
    const nlohmann::json& format = member(path, json, "", "format");
    if (format != toolpaths_format)
        throw InputError(
            path, "format",
            "expected \"" + std::string(toolpaths_format) + "\", got " + format.dump());
    if (member(path, json, "", "units") != "mm") throw InputError(path, "units", "expected \"mm\"");
    ToolpathsFile file;
    const nlohmann::json& strategy = member(path, json, "", "strategy");
    if (!strategy.is_string()) throw InputError(path, "strategy", "expected a string");
    file.strategy = strategy.get<std::string>();
    const nlohmann::json& layers = array(path, member(path, json, "", "layers"), "layers");
    file.layers.reserve(layers.size());
    for (std::size_t i = 0; i < layers.size(); ++i)
        file.layers.push_back(parse_layer(path, layers[i], "layers[" + std::to_string(i) + "]"));
    return file;
}

}  // namespace fibrecell::planner
