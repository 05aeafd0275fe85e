#include "planner/io/stress_text_reader.hpp"

#include "planner/input_error.hpp"
#include "planner/io/file_text.hpp"
#include "planner/io/number_parse.hpp"
#include "planner/io/text_fields.hpp"
#include "planner/io/text_scanner.hpp"

#include <cmath>
#include <cstdint>

namespace fibrecell::planner {

std::vector<StressTensor> parse_stress_text(std::string_view text, const std::string& file,
                                            std::size_t tet_count) {
    constexpr std::size_t kFields = 8;  // elemId,P,S11,S22,S33,S12,S13,S23
    static const char* const kNames[kFields] = {"elemId", "P",   "S11", "S22",
                                                "S33",    "S12", "S13", "S23"};
    TextScanner s(text, file);
    std::vector<StressTensor> stress(tet_count, StressTensor::Zero());
    std::vector<std::uint32_t> line_of(tet_count, 0);  // where each element was given; 0 = not yet
    std::size_t given = 0;

    std::string_view line;
    while (s.next_line(line)) {
        if (trim(line).empty()) continue;
        std::string_view fields[kFields];
        const std::size_t n = split_fields(line, ',', fields, kFields);
        if (n != kFields)
            s.fail("expected 8 comma-separated fields (elemId,P,S11,S22,S33,S12,S13,S23), found " +
                   std::to_string(n));
        const auto id = parse_integer(fields[0]);
        if (!id) s.fail("expected an element id (an integer), found '" + shown(fields[0]) + "'");
        if (*id < 1 || static_cast<unsigned long long>(*id) > tet_count)
            s.fail("element id " + std::to_string(*id) + " is outside 1.." +
                   std::to_string(tet_count) + " (the mesh has " + std::to_string(tet_count) +
                   " tets)");
        const auto e = static_cast<std::size_t>(*id - 1);
        if (line_of[e] != 0)
            s.fail("element id " + std::to_string(*id) + " appears twice (first on line " +
                   std::to_string(line_of[e]) + ")");
        line_of[e] = static_cast<std::uint32_t>(s.line());
        ++given;

        double c[kFields];
        for (std::size_t k = 1; k < kFields; ++k) {
            const auto v = parse_real(fields[k]);
            if (!v)
                s.fail(std::string("expected ") + kNames[k] + " (a number), found '" +
                       shown(fields[k]) + "'");
            if (!std::isfinite(*v))
                s.fail(std::string(kNames[k]) + " is not a finite number: '" + shown(fields[k]) +
                       "'");
            c[k] = *v;
        }
        stress[e] << c[2], c[5], c[6],  //
            c[5], c[3], c[7],           //
            c[6], c[7], c[4];
    }
    if (given != tet_count) {
        std::size_t missing = 0;
        while (line_of[missing] != 0) ++missing;
        throw InputError(file, "element " + std::to_string(missing + 1),
                         "no stress line for this element: " + std::to_string(given) + " of " +
                             std::to_string(tet_count) + " elements given");
    }
    return stress;
}

std::vector<StressTensor> read_stress_text(const std::string& path, std::size_t tet_count) {
    return parse_stress_text(read_file_text(path), path, tet_count);
}

}  // namespace fibrecell::planner
