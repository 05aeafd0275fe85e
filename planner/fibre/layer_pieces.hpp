#pragma once
// A layer can cut the part into separate pieces; each gets its own scalar-field range and
// isocurve count.

#include "planner/layers/layer_mesh.hpp"

#include <vector>

namespace fibrecell::planner {

struct LayerPiece {
    LayerMesh mesh;                    // the piece alone, vertices renumbered
    std::vector<int> vertex_of_layer;  // piece vertex -> vertex of the whole layer
    std::vector<int> face_of_layer;    // piece triangle -> triangle of the whole layer
};

// Splits `layer` into edge-connected pieces (triangles sharing an edge stay together).
std::vector<LayerPiece> split_pieces(const LayerMesh& layer);

// Shortest path lengths along mesh edges [mm] from the `sources` to every vertex (Dijkstra);
// unreachable vertices get infinity.
std::vector<double> edge_distances(const LayerMesh& mesh, const std::vector<int>& sources);

}  // namespace fibrecell::planner
