// Feeds the bytes to the .tet mesh reader (planner/io/tet_reader.hpp) as a whole file. A mesh
// or an InputError is the contract; anything else (crash, sanitizer report, other exception) is a
// finding.
#include "planner/input_error.hpp"
#include "planner/io/tet_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        fibrecell::planner::parse_tet_mesh(text, "fuzz.tet");
    } catch (const fibrecell::planner::InputError&) {
    }
    return 0;
}
