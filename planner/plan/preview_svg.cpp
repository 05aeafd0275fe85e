#include "planner/plan/preview_svg.hpp"


#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

// viridis (matplotlib) at ten evenly spaced stops, interpolated linearly in between.
constexpr std::array<std::array<int, 3>, 10> viridis_stops{{{0x44, 0x01, 0x54},
                                                            {0x48, 0x28, 0x78},
                                                            {0x3e, 0x49, 0x89},
                                                            {0x31, 0x68, 0x8e},
                                                            {0x26, 0x82, 0x8e},
                                                            {0x1f, 0x9e, 0x89},
                                                            {0x35, 0xb7, 0x79},
                                                            {0x6e, 0xce, 0x58},
                                                            {0xb5, 0xde, 0x2b},
                                                            {0xfd, 0xe7, 0x25}}};

std::string viridis_hex(double t) {
    t = std::clamp(t, 0.0, 1.0) * (viridis_stops.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(t), viridis_stops.size() - 2);
    const double f = t - static_cast<double>(i);
    char hex[8];
    int rgb[3];
    for (std::size_t c = 0; c < 3; ++c)
        rgb[c] = static_cast<int>(
            std::lround((1 - f) * viridis_stops[i][c] + f * viridis_stops[i + 1][c]));
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
    return hex;
}

// Model [mm] to SVG user units [mm]: shifted into the view, y flipped so that y points up.
struct Frame {
    Eigen::AlignedBox2d view;
    double margin = 0;

    double width() const { return view.sizes().x() + 2 * margin; }
    double height() const { return view.sizes().y() + 2 * margin; }
};

void append_svg_number(std::string& out, double value) {
    double rounded = std::round(value * 1e3) / 1e3;  // 1 um is far below a pixel
    if (rounded == 0) rounded = 0;
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, rounded);
    out.append(buffer, result.ptr);
}

void append_point(std::string& out, const Frame& frame, const Eigen::Vector2d& p) {
    append_svg_number(out, p.x() - frame.view.min().x() + frame.margin);
    out += ' ';
    append_svg_number(out, frame.view.max().y() - p.y() + frame.margin);
}

void append_polyline_d(std::string& out, const Frame& frame,
                       const std::vector<Eigen::Vector2d>& points, bool closed) {
    for (std::size_t i = 0; i < points.size(); ++i) {
        out += i == 0 ? "M" : " L";
        append_point(out, frame, points[i]);
    }
    if (closed) out += " Z";
}

Eigen::AlignedBox2d extent(const ToolpathLayer& layer, const LayerOutline* outline) {
    Eigen::AlignedBox2d box;
    for (const Toolpath& path : layer.paths)
        for (const Eigen::Vector2d& p : path.points) box.extend(p);
    if (outline)
        for (const Polygon& loop : outline->loops)
            for (const Eigen::Vector2d& p : loop) box.extend(p);
    return box;
}

void append_background(std::string& out, const Frame& frame, const TriangleScalars& scalars) {
    if (!scalars.mesh) throw std::invalid_argument("preview background without a mesh");
    const LayerMesh& mesh = *scalars.mesh;
    if (scalars.values.size() != mesh.triangles.size())
        throw std::invalid_argument("preview background has " +
                                    std::to_string(scalars.values.size()) + " values for " +
                                    std::to_string(mesh.triangles.size()) + " triangles");
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (double v : scalars.values)
        if (std::isfinite(v)) {
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    // One path per colour step: 64 steps of the map are more than a preview shows, and a few
    // dozen elements instead of one per triangle keep the file small and a browser quick.
    constexpr int steps = 64;
    std::vector<std::string> step_d(steps);
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const double v = scalars.values[f];
        if (!std::isfinite(v)) continue;
        const double t = hi > lo ? (v - lo) / (hi - lo) : 0.5;
        std::string& d = step_d[static_cast<std::size_t>(std::clamp(static_cast<int>(t * steps), 0, steps - 1))];
        for (std::size_t k = 0; k < 3; ++k) {
            const int vertex = mesh.triangles[f][k];
            if (vertex < 0 || static_cast<std::size_t>(vertex) >= mesh.vertices.size())
                throw std::invalid_argument("preview background triangle " + std::to_string(f) +
                                            " has a vertex index out of range");
            d += k == 0 ? (d.empty() ? "M" : " M") : " L";
            append_point(d, frame, mesh.vertices[static_cast<std::size_t>(vertex)]);
        }
        d += "Z";
    }
    out += "<g class=\"field-map\" stroke-width=\"0.05\">\n";
    for (int i = 0; i < steps; ++i) {
        if (step_d[static_cast<std::size_t>(i)].empty()) continue;
        const std::string colour = viridis_hex((i + 0.5) / steps);
        out += "<path class=\"field\" fill=\"" + colour + "\" stroke=\"" + colour + "\" d=\"" +
               step_d[static_cast<std::size_t>(i)] + "\"/>\n";
    }
    out += "</g>\n";
}

constexpr const char* svg_style =
    ".outline{stroke:#9a9a9a;stroke-width:0.15}"
    ".travel{fill:none;stroke:#a0a0a0;stroke-width:0.08;stroke-dasharray:0.6 0.4}"
    ".perimeter,.infill,.fibre,.fibre-boundary{fill:none;stroke-linejoin:round;"
    "stroke-linecap:round}"
    ".perimeter{stroke:#1f5fbf}.infill{stroke:#f28e2b}"
    ".fibre{stroke:#d62728}.fibre-boundary{stroke:#111111}"
    "text{font:2px sans-serif;fill:#333}";

std::string fixed(double value, int decimals) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

}  // namespace

std::string preview_svg_name(int layer_index) {
    char name[32];
    std::snprintf(name, sizeof name, "layer_%04d.svg", layer_index);
    return name;
}

std::string layer_svg(const ToolpathLayer& layer, const LayerOutline* outline,
                      const TriangleScalars* background, const PreviewOptions& options) {
    if (!(options.pixels_per_mm > 0))
        throw std::invalid_argument("preview pixels_per_mm must be positive");
    Frame frame{options.view_mm.value_or(extent(layer, outline)), std::max(options.margin_mm, 0.0)};
    if (frame.view.isEmpty())
        frame.view = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));

    std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"";
    append_svg_number(out, frame.width() * options.pixels_per_mm);
    out += "\" height=\"";
    append_svg_number(out, frame.height() * options.pixels_per_mm);
    out += "\" viewBox=\"0 0 ";
    append_svg_number(out, frame.width());
    out += ' ';
    append_svg_number(out, frame.height());
    // The model point (x0, y0) [mm] is the view's top left corner: the dashboard draws the
    // robot's position on the layer with x - x0, y0 - y.
    out += "\" data-model-x0=\"";
    append_svg_number(out, frame.view.min().x() - frame.margin);
    out += "\" data-model-y0=\"";
    append_svg_number(out, frame.view.max().y() + frame.margin);
    out += "\">\n<style>";
    out += svg_style;
    out += "</style>\n<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";

    if (background) append_background(out, frame, *background);
    if (outline && !outline->loops.empty()) {
        // Light fill alone; over a scalar map only the edge, so that the map shows.
        out += "<path class=\"outline\" fill-rule=\"evenodd\" fill=\"";
        out += background ? "none" : "#ececec";
        out += "\" d=\"";
        for (std::size_t l = 0; l < outline->loops.size(); ++l) {
            if (l > 0) out += ' ';
            append_polyline_d(out, frame, outline->loops[l], true);
        }
        out += "\"/>\n";
    }
    if (options.show_travel) {
        for (std::size_t i = 1; i < layer.paths.size(); ++i) {
            const Toolpath& from = layer.paths[i - 1];
            const Toolpath& to = layer.paths[i];
            if (from.points.empty() || to.points.empty()) continue;
            const Eigen::Vector2d end = from.closed ? from.points.front() : from.points.back();
            out += "<path class=\"travel\" d=\"";
            append_polyline_d(out, frame, {end, to.points.front()}, false);
            out += "\"/>\n";
        }
    }
    if (options.ribbon_mm > 0 && layer.head == Head::ccf) {
        // One group's opacity, not each path's: overlapping ribbons are not drawn brighter.
        out += "<g class=\"ribbons\" opacity=\"0.45\" fill=\"none\" stroke=\"#ffffff\" "
               "stroke-linejoin=\"round\" stroke-width=\"";
        append_svg_number(out, options.ribbon_mm);
        out += "\">\n";
        for (const Toolpath& path : layer.paths) {
            if (path.points.size() < 2) continue;
            out += "<path d=\"";
            append_polyline_d(out, frame, path.points, path.closed);
            out += "\"/>\n";
        }
        out += "</g>\n";
    }
    out += "<g stroke-width=\"";
    append_svg_number(out, options.path_width_mm);
    out += "\">\n";
    for (const Toolpath& path : layer.paths) {
        if (path.points.empty()) continue;
        out += "<path class=\"";
        out += to_string(path.role);
        out += "\" d=\"";
        append_polyline_d(out, frame, path.points, path.closed);
        out += "\"/>\n";
    }
    out += "</g>\n<text x=\"1\" y=\"2.5\">layer " + std::to_string(layer.index + 1) + " (" +
           std::string(to_string(layer.head)) + ") z = " + fixed(layer.z, 3) + " mm</text>\n";
    out += "</svg>\n";
    return out;
}

std::string preview_index_html(const std::vector<ToolpathLayer>& layers,
                               const std::vector<PreviewFigure>& figures) {
    std::string out =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<title>fibrecell layer preview</title>\n<style>\n"
        "body{font-family:sans-serif;margin:1em;display:flex;gap:1.5em}\n"
        "#list{max-height:90vh;overflow-y:auto;min-width:18em}\n"
        "#list li.current{font-weight:bold}\n"
        "#view{max-width:100%;max-height:80vh;border:1px solid #ccc}\n"
        ".pla{color:#1f5fbf}.ccf{color:#d62728}\n"
        "#figures{display:flex;flex-wrap:wrap;gap:1em}#figures figure{margin:0}\n"
        "</style>\n</head>\n<body>\n<ol id=\"list\" start=\"0\">\n";
    for (const ToolpathLayer& layer : layers) {
        const std::string head(to_string(layer.head));
        out += "<li class=\"" + head + "\"><a href=\"" + preview_svg_name(layer.index) + "\">" +
               "layer " + std::to_string(layer.index + 1) + ": " + head + ", z = " + fixed(layer.z, 3) +
               " mm, " + std::to_string(layer.paths.size()) + " paths</a></li>\n";
    }
    out += "</ol>\n<main>\n<p><input id=\"slider\" type=\"range\" min=\"0\" max=\"" +
           std::to_string(layers.empty() ? 0 : layers.size() - 1) +
           "\" value=\"0\" style=\"width:30em\"> <span id=\"caption\"></span></p>\n";
    out += "<img id=\"view\" alt=\"layer preview\"" +
           (layers.empty() ? std::string()
                           : " src=\"" + preview_svg_name(layers.front().index) + "\"") +
           ">\n";
    if (!figures.empty()) {
        out += "<h2>Analyses</h2>\n<div id=\"figures\">\n";
        for (const PreviewFigure& f : figures)
            out += "<figure><img src=\"" + f.file.name + "\" alt=\"" + f.caption +
                   "\"><figcaption>" + f.caption + "</figcaption></figure>\n";
        out += "</div>\n";
    }
    out += "</main>\n";
    out +=
        "<script>\n"
        "const entries = Array.from(document.querySelectorAll('#list li'));\n"
        "const slider = document.getElementById('slider');\n"
        "function show(i) {\n"
        "  if (!entries.length) return;\n"
        "  entries.forEach((e, k) => e.classList.toggle('current', k === i));\n"
        "  const a = entries[i].querySelector('a');\n"
        "  document.getElementById('view').src = a.getAttribute('href');\n"
        "  document.getElementById('caption').textContent = a.textContent;\n"
        "  slider.value = i;\n"
        "}\n"
        "slider.addEventListener('input', () => show(Number(slider.value)));\n"
        "entries.forEach((e, k) => e.querySelector('a').addEventListener('click', ev => {\n"
        "  ev.preventDefault(); show(k);\n"
        "}));\n"
        "show(0);\n"
        "</script>\n</body>\n</html>\n";
    return out;
}

std::vector<PreviewFile> preview_files(const std::vector<ToolpathLayer>& layers,
                                       const std::vector<LayerOutline>& outlines,
                                       const std::vector<const TriangleScalars*>& backgrounds,
                                       PreviewOptions options,
                                       const std::vector<PreviewFigure>& figures) {
    if (!outlines.empty() && outlines.size() != layers.size())
        throw std::invalid_argument("preview: " + std::to_string(outlines.size()) +
                                    " outlines for " + std::to_string(layers.size()) + " layers");
    if (!backgrounds.empty() && backgrounds.size() != layers.size())
        throw std::invalid_argument("preview: " + std::to_string(backgrounds.size()) +
                                    " backgrounds for " + std::to_string(layers.size()) +
                                    " layers");
    if (!options.view_mm) {
        Eigen::AlignedBox2d view;
        for (std::size_t i = 0; i < layers.size(); ++i)
            view.extend(extent(layers[i], outlines.empty() ? nullptr : &outlines[i]));
        if (!view.isEmpty()) options.view_mm = view;
    }
    std::vector<PreviewFile> files;
    files.reserve(layers.size() + figures.size() + 1);
    for (std::size_t i = 0; i < layers.size(); ++i)
        files.push_back({preview_svg_name(layers[i].index),
                         layer_svg(layers[i], outlines.empty() ? nullptr : &outlines[i],
                                   backgrounds.empty() ? nullptr : backgrounds[i], options)});
    for (const PreviewFigure& f : figures) files.push_back(f.file);
    files.push_back({"index.html", preview_index_html(layers, figures)});
    return files;
}

}  // namespace fibrecell::planner
