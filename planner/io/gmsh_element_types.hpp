#pragma once
// The Gmsh element types a mesh file may contain: node count (needed to parse MSH 2 element
// lines), dimension and name (for messages).

#include <optional>
#include <string_view>

namespace fibrecell::planner {

struct GmshElementType {
    int id;
    int nodes;
    int dimension;
    std::string_view name;
};

constexpr int kGmshTriangle = 2;
constexpr int kGmshTetrahedron = 4;
constexpr int kGmshTetrahedron10 = 11;

// The type with Gmsh id `id`, or nullopt for ids this reader does not know.
std::optional<GmshElementType> gmsh_element_type(long long id);

}  // namespace fibrecell::planner
