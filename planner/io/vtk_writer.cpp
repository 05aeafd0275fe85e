#include "planner/io/vtk_writer.hpp"

#include <bit>
#include <charconv>
#include <cstring>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

// Appends numbers in either encoding: big-endian binary (the legacy VTK convention) or text.
class VtkOut {
  public:
    explicit VtkOut(VtkEncoding encoding) : binary_(encoding == VtkEncoding::binary) {}

    void text(std::string_view s) { out_ += s; }
    template <class T>
    void value(T v) {
        if (binary_) {
            unsigned char bytes[sizeof(T)];
            std::memcpy(bytes, &v, sizeof(T));
            if constexpr (std::endian::native == std::endian::little)
                for (std::size_t i = 0; i < sizeof(T) / 2; ++i)
                    std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
            out_.append(reinterpret_cast<const char*>(bytes), sizeof(T));
        } else {
            char buf[32];
            const auto r = std::to_chars(buf, buf + sizeof(buf), v);
            out_.append(buf, r.ptr);
            out_ += ' ';
        }
    }
    void end_row() {
        if (!binary_) out_.back() = '\n';
    }
    std::string& str() { return out_; }

  private:
    bool binary_;
    std::string out_;
};

}  // namespace

std::string field_vtk_text(const TetMesh& mesh, const FieldArrays& arrays, VtkEncoding encoding) {
    const std::size_t nt = mesh.tets.size();
    VtkOut out(encoding);
    out.str().reserve(mesh.vertices.size() * 40 + nt * 200);
    out.text("# vtk DataFile Version 3.0\nfibrecell field\n");
    out.text(encoding == VtkEncoding::binary ? "BINARY\n" : "ASCII\n");
    out.text("DATASET UNSTRUCTURED_GRID\nPOINTS " + std::to_string(mesh.vertices.size()) +
             " double\n");
    for (const auto& v : mesh.vertices) {
        for (int k = 0; k < 3; ++k) out.value(v[k]);
        out.end_row();
    }
    out.text("\nCELLS " + std::to_string(nt) + " " + std::to_string(nt * 5) + "\n");
    for (const Tet& t : mesh.tets) {
        out.value<std::int32_t>(4);
        for (int v : t) out.value<std::int32_t>(v);
        out.end_row();
    }
    out.text("\nCELL_TYPES " + std::to_string(nt) + "\n");
    for (std::size_t i = 0; i < nt; ++i) {
        out.value<std::int32_t>(10);  // VTK_TETRA
        out.end_row();
    }
    out.text("\nCELL_DATA " + std::to_string(nt) + "\n");
    if (arrays.stress) {
        out.text("TENSORS stress double\n");
        for (const auto& s : *arrays.stress) {
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) out.value(s(r, c));
            out.end_row();
        }
        out.text("\n");
    }
    if (arrays.sigma_e) {
        out.text("SCALARS sigma_e double 1\nLOOKUP_TABLE default\n");
        for (double s : *arrays.sigma_e) {
            out.value(s);
            out.end_row();
        }
        out.text("\n");
    }
    if (arrays.v_e) {
        out.text("VECTORS v_e double\n");
        for (const auto& v : *arrays.v_e) {
            for (int k = 0; k < 3; ++k) out.value(v[k]);
            out.end_row();
        }
        out.text("\n");
    }
    if (arrays.v_defined) {
        out.text("SCALARS v_defined int 1\nLOOKUP_TABLE default\n");
        for (auto d : *arrays.v_defined) {
            out.value<std::int32_t>(d);
            out.end_row();
        }
        out.text("\n");
    }
    return std::move(out.str());
}

}  // namespace fibrecell::planner
