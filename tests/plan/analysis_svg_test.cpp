// The analysis charts of preview/: what they draw, read back from the SVG text.

#include "planner/plan/analysis_svg.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <string>
#include <vector>

using namespace fibrecell::planner;

namespace {

// The values of `attribute` on every element with class `cls`, in document order.
std::vector<double> attribute_of(const std::string& svg, const std::string& cls,
                                 const std::string& attribute) {
    std::vector<double> out;
    const std::regex element("<[a-z]+ class=\"" + cls + "\"[^>]*>");
    const std::regex value(" " + attribute + "=\"([-0-9.]+)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), element);
         it != std::sregex_iterator(); ++it) {
        std::smatch m;
        const std::string tag = it->str();
        if (std::regex_search(tag, m, value)) out.push_back(std::stod(m[1]));
    }
    return out;
}

}  // namespace

TEST(AnalysisSvg, HistogramBarsAreProportionalToTheirPairs) {
    DotHistogram dots;
    for (int i = 0; i < 30; ++i) dots.add(0.95);
    for (int i = 0; i < 10; ++i) dots.add(-0.05);  // the bin [-0.1, 0)
    dots.add(1.0);                                 // +1 exactly: the last bin
    dots.add(-1.0);                                // -1 exactly: the first bin
    const std::string svg = neighbour_dots_svg(dots, 0.5);
    const std::vector<double> heights = attribute_of(svg, "bar", "height");
    ASSERT_EQ(heights.size(), static_cast<std::size_t>(DotHistogram::bin_count));
    EXPECT_NEAR(heights[19] / heights[9], 31.0 / 10.0, 0.02);
    EXPECT_NEAR(heights[0] / heights[9], 1.0 / 10.0, 0.02);
    for (int b : {1, 5, 10, 18}) EXPECT_EQ(heights[b], 0.0) << b;
    // Bars run left to right in bin order, and the eta line sits between bins 14 and 15.
    const std::vector<double> x = attribute_of(svg, "bar", "x");
    EXPECT_TRUE(std::is_sorted(x.begin(), x.end()));
    EXPECT_NE(svg.find("class=\"eta\" d=\"M"), std::string::npos);
    EXPECT_NE(svg.find("eta = 0.50"), std::string::npos);
}

TEST(AnalysisSvg, SweepPointsRiseWithTheirFibreLength) {
    ParameterSweep sweep{"p", {0, 1, 2}, {}};
    sweep.points = {{.value = 0, .fibre_length_mm = 3000},
                    {.value = 1, .fibre_length_mm = 2000},
                    {.value = 2, .fibre_length_mm = 1000}};
    const std::string svg = sweep_svg(sweep);
    const std::vector<double> cx = attribute_of(svg, "point", "cx");
    const std::vector<double> cy = attribute_of(svg, "point", "cy");
    ASSERT_EQ(cx.size(), 3u);
    ASSERT_EQ(cy.size(), 3u);
    EXPECT_LT(cx[0], cx[1]);
    EXPECT_LT(cx[1], cx[2]);
    // y down in SVG: the longest at the top, equal steps for equal differences.
    EXPECT_LT(cy[0], cy[1]);
    EXPECT_NEAR(cy[1] - cy[0], cy[2] - cy[1], 0.11);
    EXPECT_NE(svg.find("3.00 m"), std::string::npos);
}
