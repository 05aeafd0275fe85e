#include "planner/io/vtk_values.hpp"

#include "planner/io/number_parse.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace fibrecell::planner {
namespace {

struct TypeName {
    std::string_view name;
    VtkScalar type;
};

// vtkIdType is written as 32-bit int by the legacy writer; "long" is 64-bit on the platforms that
// write these files.
constexpr std::array kTypeNames = {
    TypeName{"bit", VtkScalar::bit},
    TypeName{"char", VtkScalar::int8},
    TypeName{"signed_char", VtkScalar::int8},
    TypeName{"unsigned_char", VtkScalar::uint8},
    TypeName{"short", VtkScalar::int16},
    TypeName{"unsigned_short", VtkScalar::uint16},
    TypeName{"int", VtkScalar::int32},
    TypeName{"unsigned_int", VtkScalar::uint32},
    TypeName{"long", VtkScalar::int64},
    TypeName{"unsigned_long", VtkScalar::uint64},
    TypeName{"vtkIdType", VtkScalar::int32},
    TypeName{"vtktypeint8", VtkScalar::int8},
    TypeName{"vtktypeuint8", VtkScalar::uint8},
    TypeName{"vtktypeint16", VtkScalar::int16},
    TypeName{"vtktypeuint16", VtkScalar::uint16},
    TypeName{"vtktypeint32", VtkScalar::int32},
    TypeName{"vtktypeuint32", VtkScalar::uint32},
    TypeName{"vtktypeint64", VtkScalar::int64},
    TypeName{"vtktypeuint64", VtkScalar::uint64},
    TypeName{"float", VtkScalar::float32},
    TypeName{"double", VtkScalar::float64},
    TypeName{"vtktypefloat32", VtkScalar::float32},
    TypeName{"vtktypefloat64", VtkScalar::float64},
    TypeName{"string", VtkScalar::string},
    TypeName{"utf8_string", VtkScalar::string},
};

std::size_t byte_size(VtkScalar t) {
    switch (t) {
        case VtkScalar::int8:
        case VtkScalar::uint8:
            return 1;
        case VtkScalar::int16:
        case VtkScalar::uint16:
            return 2;
        case VtkScalar::int32:
        case VtkScalar::uint32:
        case VtkScalar::float32:
            return 4;
        case VtkScalar::int64:
        case VtkScalar::uint64:
        case VtkScalar::float64:
            return 8;
        case VtkScalar::bit:
        case VtkScalar::string:
            return 0;
    }
    return 0;
}

bool is_integral(VtkScalar t) {
    return t != VtkScalar::float32 && t != VtkScalar::float64 && t != VtkScalar::bit &&
           t != VtkScalar::string;
}

// A big-endian value of type T at p.
template <class T>
T load_big_endian(const char* p) {
    std::array<char, sizeof(T)> raw;
    std::memcpy(raw.data(), p, sizeof(T));
    if constexpr (std::endian::native == std::endian::little) std::reverse(raw.begin(), raw.end());
    T value;
    std::memcpy(&value, raw.data(), sizeof(T));
    return value;
}

// Calls f with the binary value at p, loaded as its own C++ type (bit and string: not called).
template <class F>
void visit_binary(const char* p, VtkScalar t, F&& f) {
    switch (t) {
        case VtkScalar::int8: f(load_big_endian<std::int8_t>(p)); return;
        case VtkScalar::uint8: f(load_big_endian<std::uint8_t>(p)); return;
        case VtkScalar::int16: f(load_big_endian<std::int16_t>(p)); return;
        case VtkScalar::uint16: f(load_big_endian<std::uint16_t>(p)); return;
        case VtkScalar::int32: f(load_big_endian<std::int32_t>(p)); return;
        case VtkScalar::uint32: f(load_big_endian<std::uint32_t>(p)); return;
        case VtkScalar::int64: f(load_big_endian<std::int64_t>(p)); return;
        case VtkScalar::uint64: f(load_big_endian<std::uint64_t>(p)); return;
        case VtkScalar::float32: f(load_big_endian<float>(p)); return;
        case VtkScalar::float64: f(load_big_endian<double>(p)); return;
        case VtkScalar::bit:
        case VtkScalar::string: return;
    }
}

// The binary value at p as a double (exact for all but 64-bit integers beyond 2^53).
double load_as_double(const char* p, VtkScalar t) {
    double out = 0;
    visit_binary(p, t, [&](auto v) { out = static_cast<double>(v); });
    return out;
}

// The binary value at p as an index: integer types only (floating types give 0); unsigned 64-bit
// values above the signed range give -1, out of range for any index anyway.
long long load_as_integer(const char* p, VtkScalar t) {
    long long out = 0;
    visit_binary(p, t, [&](auto v) {
        using V = decltype(v);
        if constexpr (std::is_same_v<V, std::uint64_t>)
            out = v > static_cast<std::uint64_t>(INT64_MAX) ? -1 : static_cast<long long>(v);
        else if constexpr (std::is_integral_v<V>)
            out = static_cast<long long>(v);
    });
    return out;
}

}  // namespace

std::optional<VtkScalar> vtk_scalar_from_name(std::string_view name) {
    for (const TypeName& t : kTypeNames)
        if (iequals(t.name, name)) return t.type;
    return std::nullopt;
}

VtkScalar read_vtk_scalar(TextScanner& scanner) {
    const std::string_view name = scanner.token("a data type");
    const auto type = vtk_scalar_from_name(name);
    if (!type) scanner.fail("unknown VTK data type '" + shown(name) + "'");
    return *type;
}

VtkValueStream::VtkValueStream(TextScanner& scanner, bool binary, long long count, VtkScalar type,
                               std::string_view what)
    : s_(scanner), binary_(binary), type_(type), what_(what) {
    if (type == VtkScalar::string || type == VtkScalar::bit)
        s_.fail(std::string(what) + ": " + (type == VtkScalar::bit ? "bit" : "string") +
                " arrays are not supported here");
    if (binary_) {
        const std::size_t size = byte_size(type);
        s_.check_count(count, size, what);
        s_.end_header_line();
        block_ = s_.bytes(static_cast<std::size_t>(count) * size, what);
    } else {
        s_.check_count(count, 2, what);  // a digit and a separator at least
    }
}

long long VtkValueStream::integer() {
    if (!is_integral(type_)) s_.fail(what_ + " must be of an integer type");
    if (!binary_) return s_.integer(what_);
    const long long v = load_as_integer(block_.data() + next_ * byte_size(type_), type_);
    ++next_;
    return v;
}

double VtkValueStream::real() {
    if (!binary_) return s_.real(what_);
    const double v = load_as_double(block_.data() + next_ * byte_size(type_), type_);
    if (!std::isfinite(v))
        s_.fail(what_ + ": value " + std::to_string(next_) + " of the binary block is not finite");
    ++next_;
    return v;
}

double VtkValueStream::any_real() {
    if (!binary_) return s_.any_real(what_);
    const double v = load_as_double(block_.data() + next_ * byte_size(type_), type_);
    ++next_;
    return v;
}

void skip_vtk_values(TextScanner& scanner, bool binary, long long count, VtkScalar type,
                     std::string_view what) {
    if (type == VtkScalar::string)
        scanner.fail(std::string(what) + ": string arrays are not supported");
    if (!binary) {
        scanner.check_count(count, 2, what);
        scanner.skip_tokens(count, what);
        return;
    }
    if (type == VtkScalar::bit)
        scanner.check_count(count < 0 ? count : (count + 7) / 8, 1, what);  // 8 values a byte
    else
        scanner.check_count(count, byte_size(type), what);
    scanner.end_header_line();
    const std::size_t bytes = type == VtkScalar::bit
                                  ? (static_cast<std::size_t>(count) + 7) / 8
                                  : static_cast<std::size_t>(count) * byte_size(type);
    scanner.bytes(bytes, what);
}

}  // namespace fibrecell::planner
