// Feeds the bytes to the Gmsh MSH reader (planner/io/msh_reader.hpp) as a whole file. A model
// or an InputError is the contract; anything else (crash, sanitizer report, other exception) is a
// finding.
#include "planner/input_error.hpp"
#include "planner/io/msh_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        fibrecell::planner::parse_msh(text, "fuzz.msh");
    } catch (const fibrecell::planner::InputError&) {
    }
    return 0;
}
