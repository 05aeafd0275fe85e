#pragma once
// preview/ of the plan directory (docs/contracts.md): one SVG per layer, paths coloured by role
// over the layer outline (and, for fibre layers, a per-triangle scalar map such as sigma), plus an
// index.html that shows them all and works offline.

#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <Eigen/Geometry>

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace fibrecell::planner {

// One value per triangle of a layer mesh, drawn under the paths with the viridis colormap
// (lowest value dark purple, highest yellow).
struct TriangleScalars {
    const LayerMesh* mesh = nullptr;  // the triangles [mm]
    std::span<const double> values;   // #F one value per triangle (non-finite: not drawn)
};

struct PreviewOptions {
    double pixels_per_mm = 4;                    // SVG width/height; the viewBox stays in mm
    double margin_mm = 2;                        // blank border around the drawing
    double path_width_mm = 0.3;                  // stroke of the toolpaths
    bool show_travel = true;                     // thin grey lines between consecutive paths
    // > 0: a CCF layer's fibre paths are also drawn as what they cover, W-wide ribbons in a
    // translucent white (overlaps not brighter): where the layer shows through, no fibre lies.
    double ribbon_mm = 0;
    std::optional<Eigen::AlignedBox2d> view_mm;  // area drawn; empty: fit this layer
};

// The file name of a layer's SVG inside preview/: "layer_0007.svg".
std::string preview_svg_name(int layer_index);

// One layer as an SVG document, y up. Paths are <path class="ROLE"> (perimeter, infill, fibre,
// fibre-boundary; travel moves class "travel"; with options.ribbon_mm, the fibre ribbons one
// <g class="ribbons">), the outline one <path class="outline">, the
// background triangles <polygon class="field">. outline and background may be null. Throws
// std::invalid_argument when the background's values do not match its mesh's triangles.
std::string layer_svg(const ToolpathLayer& layer, const LayerOutline* outline,
                      const TriangleScalars* background, const PreviewOptions& options = {});

struct PreviewFile {
    std::string name;  // inside preview/: "layer_0007.svg", "index.html"
    std::string text;
};

// A chart beside the layers (planner/plan/analysis_svg.hpp), shown under them with its caption.
struct PreviewFigure {
    PreviewFile file;  // an SVG: "neighbour_dots.svg"
    std::string caption;
};

// index.html: a slider and a list with one entry per layer (index, z, head, path count), showing
// the layer SVGs as images, then the figures. Self-contained: no external resources.
std::string preview_index_html(const std::vector<ToolpathLayer>& layers,
                               const std::vector<PreviewFigure>& figures = {});

// preview/ as files: layer_NNNN.svg for every layer, the figures and index.html. All layers share one view
// (the union of their extents) so that the slider does not jump. `outlines` and `backgrounds` are
// empty or one per layer (a null background: none). Throws std::invalid_argument on mismatched
// sizes.
std::vector<PreviewFile> preview_files(const std::vector<ToolpathLayer>& layers,
                                       const std::vector<LayerOutline>& outlines,
                                       const std::vector<const TriangleScalars*>& backgrounds,
                                       PreviewOptions options = {},
                                       const std::vector<PreviewFigure>& figures = {});

}  // namespace fibrecell::planner
