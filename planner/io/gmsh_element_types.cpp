#include "planner/io/gmsh_element_types.hpp"

#include <array>

namespace fibrecell::planner {
namespace {

// From the Gmsh reference manual, "MSH file format" (element types 1-31, 92, 93).
constexpr std::array kTypes = {
    GmshElementType{1, 2, 1, "2-node line"},
    GmshElementType{2, 3, 2, "3-node triangle"},
    GmshElementType{3, 4, 2, "4-node quadrangle"},
    GmshElementType{4, 4, 3, "4-node tetrahedron"},
    GmshElementType{5, 8, 3, "8-node hexahedron"},
    GmshElementType{6, 6, 3, "6-node prism"},
    GmshElementType{7, 5, 3, "5-node pyramid"},
    GmshElementType{8, 3, 1, "3-node line"},
    GmshElementType{9, 6, 2, "6-node triangle"},
    GmshElementType{10, 9, 2, "9-node quadrangle"},
    GmshElementType{11, 10, 3, "10-node (second-order) tetrahedron"},
    GmshElementType{12, 27, 3, "27-node hexahedron"},
    GmshElementType{13, 18, 3, "18-node prism"},
    GmshElementType{14, 14, 3, "14-node pyramid"},
    GmshElementType{15, 1, 0, "1-node point"},
    GmshElementType{16, 8, 2, "8-node quadrangle"},
    GmshElementType{17, 20, 3, "20-node hexahedron"},
    GmshElementType{18, 15, 3, "15-node prism"},
    GmshElementType{19, 13, 3, "13-node pyramid"},
    GmshElementType{20, 9, 2, "9-node incomplete triangle"},
    GmshElementType{21, 10, 2, "10-node triangle"},
    GmshElementType{22, 12, 2, "12-node incomplete triangle"},
    GmshElementType{23, 15, 2, "15-node triangle"},
    GmshElementType{24, 15, 2, "15-node incomplete triangle"},
    GmshElementType{25, 21, 2, "21-node triangle"},
    GmshElementType{26, 4, 1, "4-node line"},
    GmshElementType{27, 5, 1, "5-node line"},
    GmshElementType{28, 6, 1, "6-node line"},
    GmshElementType{29, 20, 3, "20-node tetrahedron"},
    GmshElementType{30, 35, 3, "35-node tetrahedron"},
    GmshElementType{31, 56, 3, "56-node tetrahedron"},
    GmshElementType{92, 64, 3, "64-node hexahedron"},
    GmshElementType{93, 125, 3, "125-node hexahedron"},
};

}  // namespace

std::optional<GmshElementType> gmsh_element_type(long long id) {
    for (const GmshElementType& t : kTypes)
        if (t.id == id) return t;
    return std::nullopt;
}

}  // namespace fibrecell::planner
