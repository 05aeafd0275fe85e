#include "planner/fea/stiffness_assembly.hpp"

#include <algorithm>
#include <cstdint>

namespace fibrecell::planner {
namespace {

// For each free vertex f, the free vertices g > f it shares a tet with, ascending: the
// below-diagonal blocks of block column f.
struct UpperNeighbours {
    std::vector<int> start;  // free_count + 1 offsets into `vertex`
    std::vector<int> vertex;
};

UpperNeighbours upper_neighbours(const TetMesh& mesh, const DofNumbering& dofs) {
    std::vector<std::uint64_t> edges;  // (low << 32) | high
    edges.reserve(6 * mesh.tet_count());
    for (const Tet& t : mesh.tets) {
        for (int a = 0; a < 4; ++a) {
            const int fa = dofs.free_index[t[a]];
            if (fa < 0) continue;
            for (int b = a + 1; b < 4; ++b) {
                const int fb = dofs.free_index[t[b]];
                if (fb < 0) continue;
                const auto lo = static_cast<std::uint64_t>(std::min(fa, fb));
                const auto hi = static_cast<std::uint64_t>(std::max(fa, fb));
                edges.push_back(lo << 32 | hi);
            }
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

    UpperNeighbours n;
    n.start.assign(dofs.free_count + 1, 0);
    n.vertex.reserve(edges.size());
    for (std::uint64_t e : edges) {
        ++n.start[(e >> 32) + 1];
        n.vertex.push_back(static_cast<int>(e & 0xffffffffu));
    }
    for (int f = 0; f < dofs.free_count; ++f) n.start[f + 1] += n.start[f];
    return n;
}

// Column 3f+c holds rows 3f+c..3f+2 of the diagonal block, then 3 rows per upper neighbour.
void build_pattern(const UpperNeighbours& n, const DofNumbering& dofs, SparseMatrix& k) {
    const int dof_count = dofs.dof_count();
    int* outer = k.outerIndexPtr();
    outer[0] = 0;
    for (int f = 0; f < dofs.free_count; ++f) {
        const int degree = n.start[f + 1] - n.start[f];
        for (int c = 0; c < 3; ++c) outer[3 * f + c + 1] = outer[3 * f + c] + (3 - c) + 3 * degree;
    }
    int* inner = k.innerIndexPtr();
    for (int f = 0; f < dofs.free_count; ++f) {
        for (int c = 0; c < 3; ++c) {
            int p = outer[3 * f + c];
            for (int r = c; r < 3; ++r) inner[p++] = 3 * f + r;
            for (int i = n.start[f]; i < n.start[f + 1]; ++i)
                for (int r = 0; r < 3; ++r) inner[p++] = 3 * n.vertex[i] + r;
        }
    }
    std::fill(k.valuePtr(), k.valuePtr() + outer[dof_count], 0.0);
}

}  // namespace

DofNumbering number_free_dofs(const VertexRoles& roles) {
    DofNumbering dofs;
    dofs.free_index.assign(roles.used.size(), -1);
    for (std::size_t v = 0; v < roles.used.size(); ++v)
        if (roles.used[v] && !roles.fixed[v]) dofs.free_index[v] = dofs.free_count++;
    return dofs;
}

SparseMatrix assemble_stiffness(const TetMesh& mesh, const Lame& lame, const DofNumbering& dofs,
                                std::span<const VoigtStiffness> added) {
    const UpperNeighbours n = upper_neighbours(mesh, dofs);
    const int dof_count = dofs.dof_count();
    const std::size_t nonzeros =
        6 * static_cast<std::size_t>(dofs.free_count) + 9 * n.vertex.size();

    SparseMatrix k(dof_count, dof_count);
    k.resizeNonZeros(static_cast<Eigen::Index>(nonzeros));
    build_pattern(n, dofs, k);
    const int* outer = k.outerIndexPtr();
    double* value = k.valuePtr();

    // Position of upper neighbour `hi` in the list of `lo`: block (hi, lo) starts 3 * that
    // rows below the diagonal block in each column of lo.
    auto neighbour_rank = [&](int lo, int hi) {
        const int* first = n.vertex.data() + n.start[lo];
        return static_cast<int>(std::lower_bound(first, n.vertex.data() + n.start[lo + 1], hi) -
                                first);
    };

    for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
        const Tet& t = mesh.tets[e];
        const std::array<int, 4> f = {dofs.free_index[t[0]], dofs.free_index[t[1]],
                                      dofs.free_index[t[2]], dofs.free_index[t[3]]};
        if (f[0] < 0 && f[1] < 0 && f[2] < 0 && f[3] < 0) continue;
        const TetGeometry g = tet_geometry(mesh, t);
        const VoigtStiffness* extra = nullptr;
        if (!added.empty() && !added[e].isZero()) extra = &added[e];
        // K_ab of the tet: isotropic, plus the added stiffness where the tet has one.
        auto block = [&](int a, int b) {
            Eigen::Matrix3d kab = stiffness_block(g, lame, a, b);
            if (extra) kab += stiffness_block(g, *extra, a, b);
            return kab;
        };
        for (int a = 0; a < 4; ++a) {
            if (f[a] < 0) continue;
            const Eigen::Matrix3d kaa = block(a, a);
            for (int c = 0; c < 3; ++c)
                for (int r = c; r < 3; ++r) value[outer[3 * f[a] + c] + (r - c)] += kaa(r, c);
            for (int b = 0; b < 4; ++b) {
                if (f[b] <= f[a]) continue;               // each pair once, from its lower vertex
                const Eigen::Matrix3d kba = block(b, a);  // rows b, cols a
                const int rank = neighbour_rank(f[a], f[b]);
                for (int c = 0; c < 3; ++c) {
                    const int p = outer[3 * f[a] + c] + (3 - c) + 3 * rank;
                    for (int r = 0; r < 3; ++r) value[p + r] += kba(r, c);
                }
            }
        }
    }
    return k;
}

}  // namespace fibrecell::planner
