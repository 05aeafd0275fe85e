#pragma once
// The data blocks of legacy VTK files: value types, and reading or skipping a block of values in
// either encoding (ASCII tokens, or big-endian binary right after the header line).

#include "planner/io/text_scanner.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace fibrecell::planner {

enum class VtkScalar {
    bit,
    int8,
    uint8,
    int16,
    uint16,
    int32,
    uint32,
    int64,
    uint64,
    float32,
    float64,
    string
};

// The type named in a header ("float", "unsigned_char", "vtkIdType", "vtktypeint64", ...).
std::optional<VtkScalar> vtk_scalar_from_name(std::string_view name);

// Reads `count` values of `type` that follow the current header line, one at a time, so that an
// ASCII error can name the line of the bad value. In binary files an error names the header line.
class VtkValueStream {
  public:
    VtkValueStream(TextScanner& scanner, bool binary, long long count, VtkScalar type,
                   std::string_view what);

    long long integer();  // the next value, which must be of an integer type
    double real();        // the next value as a finite double
    double any_real();    // the next value as a double, NaN and infinity passed through

  private:
    TextScanner& s_;
    bool binary_;
    VtkScalar type_;
    std::string what_;
    std::string_view block_;  // binary only
    std::size_t next_ = 0;
};

// Moves past a block of `count` values of `type` without keeping them.
void skip_vtk_values(TextScanner& scanner, bool binary, long long count, VtkScalar type,
                     std::string_view what);

// Reads the type token of a header; rejects unknown names.
VtkScalar read_vtk_scalar(TextScanner& scanner);

}  // namespace fibrecell::planner
