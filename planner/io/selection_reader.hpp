#pragma once
// Reader for the reference data's vertex selection file: which vertices are fixed (supported) and
// which carry the load (handle).

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::planner {

// One line per vertex: `vertexId:fixed:handle:` with a 1-based id and 0/1 flags (the trailing ':'
// is optional). Every id in 1..vertex_count must appear exactly once, in any order.
// Returns the groups "fixed" and "handle" (sorted 0-based vertex indices; possibly empty).
// Throws InputError naming the file and the line (or the missing vertex).
std::map<std::string, std::vector<int>> read_selection(const std::string& path,
                                                       std::size_t vertex_count);

// The same for a file already in memory; `file` names it in messages.
std::map<std::string, std::vector<int>> parse_selection(std::string_view text,
                                                        const std::string& file,
                                                        std::size_t vertex_count);

}  // namespace fibrecell::planner
