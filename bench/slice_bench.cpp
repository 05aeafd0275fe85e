// Benchmark of slicing (paper Section 4.2): the slice index, one cross-section per layer and its
// outline, on a structured part of the paper's largest size (112k tets, Shell in Table 1) and on
// the reference parts (the shared folder beside the repository; skipped, with the reason, when
// the data is missing). Run from a Release build:
//   build/release/bench/slice_bench [--reference ../shared/data/reference-fea]

#include "planner/io/read_model.hpp"
#include "planner/layers/layer_schedule.hpp"
#include "planner/layers/outline.hpp"
#include "planner/layers/placement.hpp"
#include "planner/layers/slice.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "planner/stopwatch.hpp"
#include "tests/support/shared_data.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

using namespace fibrecell::planner;

namespace {

// Places the part, cuts it at every layer of the default schedule (PLA and CCF) and prints the
// cost per step; the best of `repeats` runs, so the numbers are the machine's, not its neighbours'.
void bench_part(const std::string& name, const TetMesh& model, int repeats = 5) {
    const TetMesh placed = place_mesh(model, placement_for(model, PlacementSpec{}));
    const auto schedule = layer_schedule(part_height(placed), LayerScheduleSpec{});

    // Median rather than worst layer: on a shared machine the worst is a scheduler tick (~4 ms).
    double index_s = INFINITY, slice_s = INFINITY, outline_s = INFINITY, median_layer_s = INFINITY;
    std::size_t triangles = 0, cut_max = 0, loops = 0;
    for (int r = 0; r < repeats; ++r) {
        Stopwatch clock;
        const SliceIndex index = build_slice_index(placed);
        index_s = std::min(index_s, clock.lap());
        std::vector<LayerMesh> layers;
        std::vector<double> per_layer;
        for (const auto& layer : schedule) {
            Stopwatch one;
            layers.push_back(slice_tet_mesh(placed, index, layer.slice_z));
            per_layer.push_back(one.lap());
        }
        slice_s = std::min(slice_s, clock.lap());
        std::nth_element(per_layer.begin(), per_layer.begin() + per_layer.size() / 2,
                         per_layer.end());
        median_layer_s = std::min(median_layer_s, per_layer[per_layer.size() / 2]);
        std::size_t loop_count = 0;
        for (const auto& layer : layers) loop_count += layer_outline(layer).loops.size();
        outline_s = std::min(outline_s, clock.lap());
        triangles = 0;
        for (const auto& layer : layers) {
            triangles += layer.triangles.size();
            cut_max = std::max(cut_max, layer.triangles.size());
        }
        loops = loop_count;
    }
    const double n = static_cast<double>(schedule.size());
    std::printf("%-12s %7zu %6zu | %8.2f | %8.3f %8.3f %8.1f | %8.3f %8.1f | %7zu %6zu %6zu\n",
                name.c_str(), model.tet_count(), schedule.size(), index_s * 1e3, slice_s / n * 1e3,
                median_layer_s * 1e3, slice_s * 1e3, outline_s / n * 1e3, outline_s * 1e3,
                triangles / schedule.size(), cut_max, loops);
}

}  // namespace

int main(int argc, char** argv) {
    std::string reference = fibrecell::test::reference_fea_dir().string();
    for (int i = 1; i + 1 < argc; ++i)
        if (std::string(argv[i]) == "--reference") reference = argv[i + 1];

    std::printf("Slicing every layer of the default schedule (0.8 mm PLA + 0.05 mm CCF on each)\n");
    std::printf("times in ms; best of 5\n\n");
    std::printf("%-12s %7s %6s | %8s | %8s %8s %8s | %8s %8s | %7s %6s %6s\n", "part", "tets",
                "layers", "index", "slice/l", "median", "slice", "outl/l", "outline", "tri/l",
                "tri max", "loops");

    // 60 mm cube of 26 x 26 x 28 cells: 113,568 tets, 150 layers.
    StructuredMeshOptions cube;
    cube.size = {60, 60, 60};
    cube.cells = {26, 26, 28};
    bench_part("cube-112k", structured_tet_mesh(cube));
    // A plate like the Loop part: few, wide layers (140 x 100 x 10 mm).
    StructuredMeshOptions plate;
    plate.size = {140, 100, 10};
    plate.cells = {72, 52, 5};
    bench_part("plate-112k", structured_tet_mesh(plate));

    for (const char* part : {"bunnyhead", "YogaNew"}) {
        // Only the mesh is read here, but a data set is whole or missing.
        if (const std::string missing = fibrecell::test::reference_fea_missing(part, reference);
            !missing.empty()) {
            std::printf("%-12s skipped: %s\n", part, missing.c_str());
            continue;
        }
        const std::string base = fibrecell::test::reference_fea_stem(part, reference);
        bench_part(part, read_volume_model(base + ".tet").mesh);
    }
    return 0;
}
