#pragma once
// toolpaths.json of the plan directory (docs/contracts.md): every layer, every path, in print
// order, in the bed frame (the part as placed on the bed) [mm].

#include "planner/toolpaths/toolpath.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::planner {

// The format tag written and required by the reader.
inline constexpr std::string_view toolpaths_format = "fibrecell.toolpaths/1";

struct ToolpathsFile {
    std::string strategy;  // "field", "contour-zigzag" or "field-dense"
    std::vector<ToolpathLayer> layers;
};

// The document as text: one line per path, coordinates rounded to 1e-4 mm and printed in their
// shortest form. Throws std::invalid_argument on a non-finite number.
std::string toolpaths_json_text(std::string_view strategy,
                                const std::vector<ToolpathLayer>& layers);

// Reads a toolpaths.json back. Throws InputError naming the file and the offending key
// ("layers[2].paths[5].role: unknown role 'x'") on anything that does not follow the format.
ToolpathsFile read_toolpaths_json(const std::string& path);

}  // namespace fibrecell::planner
