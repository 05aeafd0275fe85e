#include "planner/plan/analysis_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace fibrecell::planner {
namespace {

// A plot area in SVG pixels with data ranges on both axes; y grows upwards in data.
struct Chart {
    double x0, x1, y0, y1;  // data ranges
    static constexpr double width = 480, height = 300;
    static constexpr double left = 60, right = 16, top = 34, bottom = 46;

    double px(double x) const { return left + (x - x0) / (x1 - x0) * (width - left - right); }
    double py(double y) const {
        return height - bottom - (y - y0) / (y1 - y0) * (height - top - bottom);
    }
};

std::string num(double v, int decimals = 3) {
    if (std::abs(v) < 0.5 * std::pow(10.0, -decimals)) v = 0;  // no "-0.0"
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    return b;
}

// A tick step of 1, 2 or 5 times a power of ten giving about `ticks` intervals over `span`.
double nice_step(double span, int ticks) {
    const double raw = span / ticks;
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (raw <= m * p) return m * p;
    return 10 * p;
}

int decimals_for(double step) {
    return std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
}

std::string open_svg(const std::string& title) {
    std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(Chart::width, 0) +
                      "\" height=\"" + num(Chart::height, 0) + "\" viewBox=\"0 0 " +
                      num(Chart::width, 0) + " " + num(Chart::height, 0) +
                      "\" font-family=\"sans-serif\" font-size=\"12\">\n"
                      "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
    out += "<text x=\"" + num(Chart::width / 2, 0) +
           "\" y=\"20\" text-anchor=\"middle\" font-size=\"14\">" + title + "</text>\n";
    return out;
}

void axes(std::string& out, const Chart& c, std::string_view x_label, std::string_view y_label) {
    out += "<g stroke=\"#444\" fill=\"none\"><path d=\"M" + num(c.px(c.x0), 1) + " " +
           num(c.py(c.y1), 1) + " V" + num(c.py(c.y0), 1) + " H" + num(c.px(c.x1), 1) +
           "\"/></g>\n";
    const double xs = nice_step(c.x1 - c.x0, 5), ys = nice_step(c.y1 - c.y0, 5);
    for (double x = std::ceil(c.x0 / xs - 1e-9) * xs; x <= c.x1 + 1e-9 * xs; x += xs)
        out += "<text x=\"" + num(c.px(x), 1) + "\" y=\"" + num(c.py(c.y0) + 16, 1) +
               "\" text-anchor=\"middle\">" + num(x, decimals_for(xs)) + "</text>\n";
    for (double y = std::ceil(c.y0 / ys - 1e-9) * ys; y <= c.y1 + 1e-9 * ys; y += ys)
        out += "<text x=\"" + num(c.px(c.x0) - 6, 1) + "\" y=\"" + num(c.py(y) + 4, 1) +
               "\" text-anchor=\"end\">" + num(y, decimals_for(ys)) + "</text>\n";
    out += "<text x=\"" + num((c.px(c.x0) + c.px(c.x1)) / 2, 1) + "\" y=\"" +
           num(Chart::height - 8, 1) + "\" text-anchor=\"middle\">" + std::string(x_label) +
           "</text>\n";
    out += "<text transform=\"translate(14 " + num((c.py(c.y0) + c.py(c.y1)) / 2, 1) +
           ") rotate(-90)\" text-anchor=\"middle\">" + std::string(y_label) + "</text>\n";
}

}  // namespace

std::string neighbour_dots_svg(const DotHistogram& dots, double eta) {
    const double total = static_cast<double>(std::max<std::uint64_t>(1, dots.pairs));
    double top = 0;
    for (std::uint64_t n : dots.counts) top = std::max(top, static_cast<double>(n) / total);
    const Chart c{-1, 1, 0, top > 0 ? top * 1.1 : 1};
    std::string out =
        open_svg("Neighbour directions v_e · v_e* (" + std::to_string(dots.pairs) + " pairs)");
    axes(out, c, "v_e · v_e*", "share of pairs");
    const double w = 2.0 / DotHistogram::bin_count;
    for (int b = 0; b < DotHistogram::bin_count; ++b) {
        const double lo = dots.lower_edge(b), share = static_cast<double>(dots.counts[b]) / total;
        out += "<rect class=\"bar\" x=\"" + num(c.px(lo) + 0.5, 1) + "\" y=\"" +
               num(c.py(share), 1) + "\" width=\"" + num(c.px(lo + w) - c.px(lo) - 1, 1) +
               "\" height=\"" + num(c.py(0) - c.py(share), 1) + "\" fill=\"" +
               (lo + w <= eta ? "#d62728" : "#1f77b4") + "\"/>\n";
    }
    out += "<path class=\"eta\" d=\"M" + num(c.px(eta), 1) + " " + num(c.py(c.y0), 1) + " V" +
           num(c.py(c.y1), 1) + "\" stroke=\"#000\" stroke-dasharray=\"4 3\"/>\n";
    out += "<text x=\"" + num(c.px(eta) - 4, 1) + "\" y=\"" + num(c.py(c.y1) + 12, 1) +
           "\" text-anchor=\"end\">eta = " + num(eta, 2) + ": " +
           num(100.0 * static_cast<double>(dots.at_most_eta) / total, 1) +
           "% of pairs at or below</text>\n</svg>\n";
    return out;
}

std::string sweep_svg(const ParameterSweep& sweep) {
    double x0 = 0, x1 = 1, y1 = 0;
    if (!sweep.points.empty()) {
        x0 = x1 = sweep.points.front().value;
        for (const SweepPoint& p : sweep.points) {
            x0 = std::min(x0, p.value), x1 = std::max(x1, p.value);
            y1 = std::max(y1, p.fibre_length_mm / 1000.0);
        }
        if (x1 - x0 < 1e-9) x0 -= 0.5, x1 += 0.5;
    }
    const double pad = 0.05 * (x1 - x0);
    const Chart c{x0 - pad, x1 + pad, 0, y1 > 0 ? y1 * 1.15 : 1};
    std::string out = open_svg("Fibre length against " + sweep.parameter);
    axes(out, c, sweep.parameter, "fibre length [m]");
    std::string line;
    for (const SweepPoint& p : sweep.points)
        line += (line.empty() ? "M" : " L") + num(c.px(p.value), 1) + " " +
                num(c.py(p.fibre_length_mm / 1000.0), 1);
    if (!line.empty())
        out += "<path d=\"" + line + "\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"2\"/>\n";
    for (const SweepPoint& p : sweep.points) {
        const double y = c.py(p.fibre_length_mm / 1000.0);
        out += "<circle class=\"point\" cx=\"" + num(c.px(p.value), 1) + "\" cy=\"" + num(y, 1) +
               "\" r=\"4\" fill=\"#d62728\"/>\n<text x=\"" + num(c.px(p.value), 1) + "\" y=\"" +
               num(y - 9, 1) + "\" text-anchor=\"middle\">" + num(p.fibre_length_mm / 1000.0, 2) +
               " m</text>\n";
    }
    out += "</svg>\n";
    return out;
}

}  // namespace fibrecell::planner
