#include "planner/fibre/layer_pieces.hpp"

#include "planner/fibre/layer_field.hpp"

#include <limits>
#include <queue>

namespace fibrecell::planner {

std::vector<LayerPiece> split_pieces(const LayerMesh& layer) {
    const auto neighbours = triangle_neighbours(layer);
    std::vector<int> piece_of(layer.triangles.size(), -1);
    std::vector<LayerPiece> pieces;
    for (std::size_t seed = 0; seed < layer.triangles.size(); ++seed) {
        if (piece_of[seed] >= 0) continue;
        const int id = static_cast<int>(pieces.size());
        LayerPiece& piece = pieces.emplace_back();
        piece.mesh.z = layer.z;
        std::vector<int> stack{static_cast<int>(seed)};
        piece_of[seed] = id;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            piece.face_of_layer.push_back(f);
            for (int g : neighbours[f])
                if (piece_of[g] < 0) piece_of[g] = id, stack.push_back(g);
        }
    }
    // Pieces touching at a single vertex each get their own copy of it: `stamp` says which
    // piece `local` currently numbers the vertex for.
    std::vector<int> local(layer.vertices.size(), -1), stamp(layer.vertices.size(), -1);
    for (std::size_t id = 0; id < pieces.size(); ++id) {
        LayerPiece& piece = pieces[id];
        for (int f : piece.face_of_layer) {
            std::array<int, 3> t{};
            for (int k = 0; k < 3; ++k) {
                const int v = layer.triangles[f][k];
                if (stamp[v] != static_cast<int>(id)) {
                    stamp[v] = static_cast<int>(id);
                    local[v] = static_cast<int>(piece.mesh.vertices.size());
                    piece.mesh.vertices.push_back(layer.vertices[v]);
                    piece.vertex_of_layer.push_back(v);
                }
                t[k] = local[v];
            }
            piece.mesh.triangles.push_back(t);
            piece.mesh.triangle_tet.push_back(layer.triangle_tet[f]);
        }
    }
    return pieces;
}

std::vector<double> edge_distances(const LayerMesh& mesh, const std::vector<int>& sources) {
    // Adjacency from triangle edges (each interior edge appears twice; harmless for Dijkstra).
    std::vector<std::vector<int>> adjacent(mesh.vertices.size());
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            adjacent[t[k]].push_back(t[(k + 1) % 3]);
            adjacent[t[(k + 1) % 3]].push_back(t[k]);
        }
    std::vector<double> dist(mesh.vertices.size(), std::numeric_limits<double>::infinity());
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (int s : sources) dist[s] = 0, queue.push({0.0, s});
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > dist[v]) continue;
        for (int w : adjacent[v]) {
            const double nd = d + (mesh.vertices[w] - mesh.vertices[v]).norm();
            if (nd < dist[w]) dist[w] = nd, queue.push({nd, w});
        }
    }
    return dist;
}

}  // namespace fibrecell::planner
