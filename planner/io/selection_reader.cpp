#include "planner/io/selection_reader.hpp"

#include "planner/input_error.hpp"
#include "planner/io/file_text.hpp"
#include "planner/io/number_parse.hpp"
#include "planner/io/text_fields.hpp"
#include "planner/io/text_scanner.hpp"

#include <cstdint>

namespace fibrecell::planner {

std::map<std::string, std::vector<int>> parse_selection(std::string_view text,
                                                        const std::string& file,
                                                        std::size_t vertex_count) {
    TextScanner s(text, file);
    std::map<std::string, std::vector<int>> groups{{"fixed", {}}, {"handle", {}}};
    std::vector<int>& fixed = groups["fixed"];
    std::vector<int>& handle = groups["handle"];
    std::vector<std::uint32_t> line_of(vertex_count, 0);  // 0 = not given yet
    std::size_t given = 0;

    auto flag = [&s](std::string_view field, const char* name) {
        if (field == "0") return false;
        if (field == "1") return true;
        s.fail(std::string("the ") + name + " flag must be 0 or 1, found '" + shown(field) + "'");
    };

    std::string_view line;
    while (s.next_line(line)) {
        if (trim(line).empty()) continue;
        std::string_view fields[4];
        const std::size_t n = split_fields(line, ':', fields, 4);
        if (!(n == 3 || (n == 4 && fields[3].empty())))
            s.fail("expected 'vertexId:fixed:handle:', found '" + shown(line) + "'");
        const auto id = parse_integer(fields[0]);
        if (!id) s.fail("expected a vertex id (an integer), found '" + shown(fields[0]) + "'");
        if (*id < 1 || static_cast<unsigned long long>(*id) > vertex_count)
            s.fail("vertex id " + std::to_string(*id) + " is outside 1.." +
                   std::to_string(vertex_count) + " (the mesh has " + std::to_string(vertex_count) +
                   " vertices)");
        const auto v = static_cast<std::size_t>(*id - 1);
        if (line_of[v] != 0)
            s.fail("vertex id " + std::to_string(*id) + " appears twice (first on line " +
                   std::to_string(line_of[v]) + ")");
        line_of[v] = static_cast<std::uint32_t>(s.line());
        ++given;
        if (flag(fields[1], "fixed")) fixed.push_back(static_cast<int>(v));
        if (flag(fields[2], "handle")) handle.push_back(static_cast<int>(v));
    }
    if (given != vertex_count) {
        std::size_t missing = 0;
        while (line_of[missing] != 0) ++missing;
        throw InputError(file, "vertex " + std::to_string(missing + 1),
                         "no selection line for this vertex: " + std::to_string(given) + " of " +
                             std::to_string(vertex_count) + " vertices given");
    }
    return groups;
}

std::map<std::string, std::vector<int>> read_selection(const std::string& path,
                                                       std::size_t vertex_count) {
    return parse_selection(read_file_text(path), path, vertex_count);
}

}  // namespace fibrecell::planner
