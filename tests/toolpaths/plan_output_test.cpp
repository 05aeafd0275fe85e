// The plan directory's toolpaths.json (round trip, clear errors) and preview/ (one SVG per layer,
// paths by role class, index.html with one entry per layer).

#include "planner/plan/preview_svg.hpp"
#include "planner/plan/toolpaths_json.hpp"
#include "tests/support/temp_dir.hpp"

#include "planner/input_error.hpp"
#include "planner/toolpaths/contour_zigzag.hpp"
#include "planner/toolpaths/pla_paths.hpp"
#include "toolpath_test_shapes.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fibrecell::planner {
namespace {

namespace fs = std::filesystem;

class PlanOutput : public ::testing::Test {
  protected:
    fibrecell::test::TempDir dir_{"plan-output"};
};

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++n;
    return n;
}

// A PLA layer and a CCF layer over the holed rectangle.
std::vector<ToolpathLayer> two_layers() {
    const LayerOutline outline = test::holed_rectangle_outline();
    ContourZigzagOptions fibre;
    fibre.cutter_distance_mm = 10;
    return {{0, 0.8, Head::pla, 0.8, pla_layer_paths(outline, 0)},
            {1, 0.85, Head::ccf, 0.05, contour_zigzag_paths(outline, 0, fibre).paths}};
}

TEST_F(PlanOutput, ToolpathsJsonRoundTrip) {
    const std::vector<ToolpathLayer> layers = two_layers();
    const std::string path = (dir_ / "toolpaths.json").string();
    std::ofstream(path) << toolpaths_json_text("contour-zigzag", layers);

    const ToolpathsFile file = read_toolpaths_json(path);
    EXPECT_EQ(file.strategy, "contour-zigzag");
    ASSERT_EQ(file.layers.size(), layers.size());
    for (std::size_t l = 0; l < layers.size(); ++l) {
        const ToolpathLayer& want = layers[l];
        const ToolpathLayer& got = file.layers[l];
        EXPECT_EQ(got.index, want.index);
        EXPECT_DOUBLE_EQ(got.z, want.z);
        EXPECT_EQ(got.head, want.head);
        EXPECT_DOUBLE_EQ(got.thickness, want.thickness);
        ASSERT_EQ(got.paths.size(), want.paths.size());
        for (std::size_t p = 0; p < want.paths.size(); ++p) {
            EXPECT_EQ(got.paths[p].role, want.paths[p].role);
            EXPECT_EQ(got.paths[p].closed, want.paths[p].closed);
            ASSERT_EQ(got.paths[p].points.size(), want.paths[p].points.size());
            for (std::size_t i = 0; i < want.paths[p].points.size(); ++i)
                EXPECT_LE((got.paths[p].points[i] - want.paths[p].points[i]).cwiseAbs().maxCoeff(),
                          0.5e-4 + 1e-12);
        }
    }
}

TEST_F(PlanOutput, ToolpathsJsonIsCompactAndFollowsTheContract) {
    const std::vector<ToolpathLayer> layers{
        {0, 0.8, Head::pla, 0.8, {{PathRole::perimeter, true, {{1.0 / 3, 2}, {-0.00001, 5}}}}}};
    const std::string text = toolpaths_json_text("field", layers);
    EXPECT_NE(text.find(R"("format": "fibrecell.toolpaths/1", "units": "mm", "strategy": "field")"),
              std::string::npos);
    EXPECT_NE(text.find(R"({"index": 0, "z": 0.8, "head": "pla", "thickness": 0.8, "paths": [)"),
              std::string::npos);
    EXPECT_NE(
        text.find(R"({"role": "perimeter", "closed": true, "points": [[0.3333, 2], [0, 5]]})"),
        std::string::npos)
        << text;
}

TEST_F(PlanOutput, ToolpathsJsonReaderNamesTheProblem) {
    const fs::path path = dir_ / "bad.json";
    auto expect_error = [&](const std::string& text, const std::string& where) {
        std::ofstream(path) << text;
        try {
            read_toolpaths_json(path.string());
            ADD_FAILURE() << "accepted: " << text;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
        }
    };
    expect_error("{", "not valid JSON");
    expect_error(R"({"format": "other/1"})", "format");
    expect_error(R"({"format": "fibrecell.toolpaths/1", "units": "in"})", "units");
    const std::string head =
        R"({"format": "fibrecell.toolpaths/1", "units": "mm", "strategy": "field", "layers": [)";
    expect_error(head + R"({"index": 0, "z": 1, "head": "abc", "thickness": 1, "paths": []}]})",
                 "layers[0].head");
    expect_error(head + R"({"index": 0, "z": 1, "head": "pla", "thickness": 1, "paths": [)" +
                     R"({"role": "glue", "closed": true, "points": []}]}]})",
                 "layers[0].paths[0].role: unknown role 'glue'");
    expect_error(head + R"({"index": 0, "z": 1, "head": "pla", "thickness": 1, "paths": [)" +
                     R"({"role": "infill", "closed": false, "points": [[1, 2], [3]]}]}]})",
                 "layers[0].paths[0].points[1]");
    expect_error(head + R"({"index": 0, "head": "pla", "thickness": 1, "paths": []}]})",
                 "layers[0].z: missing");
    EXPECT_THROW(read_toolpaths_json((dir_ / "missing.json").string()), InputError);
}

TEST_F(PlanOutput, PreviewWritesOneSvgPerLayerAndAnIndex) {
    const std::vector<ToolpathLayer> layers = two_layers();
    const LayerOutline outline = test::holed_rectangle_outline();
    // A two-triangle mesh under the fibre layer with one value per triangle.
    LayerMesh mesh;
    mesh.vertices = {{0, 0}, {30, 0}, {30, 20}, {0, 20}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    mesh.triangle_tet = {0, 1};
    const std::vector<double> sigma{1.0, 3.0};
    const TriangleScalars background{&mesh, sigma};

    std::map<std::string, std::string> files;
    for (auto& f : preview_files(layers, {outline, outline}, {nullptr, &background}))
        files[f.name] = std::move(f.text);
    ASSERT_EQ(files.size(), layers.size() + 1);

    for (const ToolpathLayer& layer : layers) {
        const std::string svg = files[preview_svg_name(layer.index)];
        ASSERT_FALSE(svg.empty());
        EXPECT_EQ(svg.rfind("<svg", 0), 0u);
        for (PathRole role :
             {PathRole::perimeter, PathRole::infill, PathRole::fibre, PathRole::fibre_boundary}) {
            std::size_t want = 0;
            for (const Toolpath& path : layer.paths) want += path.role == role;
            EXPECT_EQ(count(svg, "<path class=\"" + std::string(to_string(role)) + "\""), want)
                << to_string(role) << " in layer " << layer.index;
        }
        EXPECT_EQ(count(svg, "<path class=\"travel\""), layer.paths.size() - 1);
        EXPECT_EQ(count(svg, "<path class=\"outline\""), 1u);
        // The map: one path per colour step (sigma 1 and 3: the two ends of the scale), each
        // triangle a closed sub-path of three points.
        EXPECT_EQ(count(svg, "<path class=\"field\""), layer.head == Head::ccf ? 2u : 0u);
        const auto map_at = svg.find("<g class=\"field-map\"");
        const std::string map = map_at == std::string::npos ? ""
                                                            : svg.substr(map_at, svg.find("</g>", map_at) - map_at);
        EXPECT_EQ(count(map, "Z"), layer.head == Head::ccf ? 2u : 0u);
    }
    EXPECT_TRUE(files.contains("layer_0001.svg"));
    const std::string index = files["index.html"];
    EXPECT_EQ(count(index, "<li"), layers.size());
    EXPECT_EQ(count(index, "href=\"layer_0000.svg\""), 1u);
    EXPECT_EQ(count(index, "href=\"layer_0001.svg\""), 1u);
    EXPECT_EQ(count(index, "http"), 0u);  // works offline
}

TEST_F(PlanOutput, SvgHasYUp) {
    const ToolpathLayer layer{
        0, 0.8, Head::pla, 0.8, {{PathRole::infill, false, {{0, 0}, {10, 10}}}}};
    PreviewOptions options;
    options.margin_mm = 2;
    const std::string svg = layer_svg(layer, nullptr, nullptr, options);
    EXPECT_NE(svg.find("viewBox=\"0 0 14 14\""), std::string::npos) << svg;
    EXPECT_NE(svg.find("d=\"M2 12 L12 2\""), std::string::npos) << svg;  // (0,0) bottom-left
}

TEST_F(PlanOutput, AFibreLayerShowsTheRibbonsItsPathsLay) {
    const ToolpathLayer fibre{1, 0.85, Head::ccf, 0.05,
                              {{PathRole::fibre, false, {{0, 0}, {10, 0}}},
                               {PathRole::fibre_boundary, true, {{0, 2}, {10, 2}, {10, 4}}}}};
    const ToolpathLayer pla{0, 0.8, Head::pla, 0.8, {{PathRole::infill, false, {{0, 0}, {10, 10}}}}};
    PreviewOptions options;
    options.margin_mm = 0;
    options.ribbon_mm = 1.1;
    const std::string svg = layer_svg(fibre, nullptr, nullptr, options);
    const auto at = svg.find("<g class=\"ribbons\"");
    ASSERT_NE(at, std::string::npos) << svg;
    const std::string ribbons = svg.substr(at, svg.find("</g>", at) - at);
    EXPECT_NE(ribbons.find("stroke-width=\"1.1\""), std::string::npos) << ribbons;
    EXPECT_EQ(count(ribbons, "<path d="), 2u);  // one per fibre path, rings too
    EXPECT_EQ(count(ribbons, "Z"), 1u);         // the ring closed
    // Under the paths, so that the paths show on top.
    EXPECT_LT(at, svg.find("<path class=\"fibre\""));
    EXPECT_EQ(layer_svg(pla, nullptr, nullptr, options).find("ribbons"), std::string::npos);
    options.ribbon_mm = 0;
    EXPECT_EQ(layer_svg(fibre, nullptr, nullptr, options).find("ribbons"), std::string::npos);
}

TEST_F(PlanOutput, PreviewRejectsMismatchedInputs) {
    const std::vector<ToolpathLayer> layers = two_layers();
    EXPECT_THROW(preview_files(layers, {LayerOutline{}}, {}), std::invalid_argument);
    LayerMesh mesh;
    mesh.vertices = {{0, 0}, {1, 0}, {0, 1}};
    mesh.triangles = {{0, 1, 2}};
    const std::vector<double> values{1.0, 2.0};
    const TriangleScalars wrong{&mesh, values};
    EXPECT_THROW(layer_svg(layers[0], nullptr, &wrong), std::invalid_argument);
}

}  // namespace
}  // namespace fibrecell::planner
