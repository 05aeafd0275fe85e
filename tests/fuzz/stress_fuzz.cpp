// Feeds the bytes to the reference data's per-element stress reader and vertex selection reader
// (planner/io/stress_text_reader.hpp, selection_reader.hpp), expecting one entry per line. A
// result or an InputError is the contract; anything else is a finding.
#include "planner/input_error.hpp"
#include "planner/io/selection_reader.hpp"
#include "planner/io/stress_text_reader.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    // A well-formed file has one line per element (vertex): let the line count be the mesh's, so
    // that the seeds are accepted and a mutation is checked against the counts they imply.
    const auto count = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    try {
        fibrecell::planner::parse_stress_text(text, "fuzz_stress.txt", count);
    } catch (const fibrecell::planner::InputError&) {
    }
    try {
        fibrecell::planner::parse_selection(text, "fuzz_selection.txt", count);
    } catch (const fibrecell::planner::InputError&) {
    }
    return 0;
}
