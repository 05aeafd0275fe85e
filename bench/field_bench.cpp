// Benchmark of the 3D vector-field stage (paper Section 4.1, Table 1) on parts of the paper's
// sizes: FEA solve, reading the stressed mesh back from ASCII VTK, principal stresses, MST
// re-orientation and incompatibility removal. Also measures the fraction of elements each
// reading of Eq. 2 removes on the reference data (the shared folder beside the repository; that
// part is skipped, with the reason, when the data is missing). Run from a Release build:
//   build/release/bench/field_bench [--reference ../shared/data/reference-fea]
//   build/release/bench/field_bench --tets N     one plate of about N tets, with the peak memory
//                                                 (the FEA's cost at the part limits' max_tets)

#include "bench_parts.hpp"
#include "config/durable_file.hpp"
#include "planner/fea/linear_elastic.hpp"
#include "planner/field/incompatibility.hpp"
#include "planner/field/mst_reorientation.hpp"
#include "planner/field/tensile_field.hpp"
#include "planner/io/read_model.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/mesh/adjacency.hpp"
#include "planner/stopwatch.hpp"
#include "tests/support/shared_data.hpp"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

using namespace fibrecell::planner;
using fibrecell::bench::end_load;
using fibrecell::bench::loop_like_plate;

namespace {

// The paper's Table 1 (i7-9750H, 6 cores): tets, MST re-orientation [s], incompatibility [s].
struct PaperRow {
    const char* model;
    int tets;
    double mst_s;
    double removal_s;
};
constexpr PaperRow kPaper[] = {{"Wrench", 14002, 2.883, 0.329},
                               {"Loop", 32473, 17.684, 0.810},
                               {"Piston", 85558, 215.88, 2.501},
                               {"Shell", 112080, 400.683, 3.262}};

struct FieldTimes {
    double principal = 0, mst = 0, removal = 0;
    // Fractions removed under the readings of Eq. 2, and the vertex-connected clusters they form.
    struct Reading {
        double fraction = 0;
        int clusters = 0, largest = 0;
    };
    Reading all, majority, any;
};

// Groups the undefined elements into clusters of vertex-sharing neighbours: scattered single
// elements or regions?
std::pair<int, int> removed_clusters(const std::vector<std::uint8_t>& defined,
                                     const CsrGraph& around) {
    std::vector<char> seen(defined.size(), 0);
    int clusters = 0, largest = 0;
    for (std::size_t e = 0; e < defined.size(); ++e) {
        if (defined[e] || seen[e]) continue;
        ++clusters;
        int size = 0;
        std::vector<int> stack{static_cast<int>(e)};
        seen[e] = 1;
        while (!stack.empty()) {
            const int x = stack.back();
            stack.pop_back();
            ++size;
            for (int n : around.neighbours(x))
                if (!defined[n] && !seen[n]) seen[n] = 1, stack.push_back(n);
        }
        largest = std::max(largest, size);
    }
    return {clusters, largest};
}

FieldTimes run_field(const TetMesh& mesh, const std::vector<StressTensor>& stress) {
    FieldTimes t;
    Stopwatch clock;
    TensileField field = tensile_field(stress);
    t.principal = clock.lap();
    const FaceNeighbours faces = face_neighbours(mesh);
    mst_reorient(field.v_e, field.sigma_e, faces);
    t.mst = clock.lap();
    const CsrGraph around = vertex_sharing_neighbours(mesh);
    const auto defined = compatible_directions(field.v_e, around);
    t.removal = clock.lap();
    auto reading = [&](const std::vector<std::uint8_t>& d) {
        FieldTimes::Reading r;
        r.fraction =
            static_cast<double>(std::count(d.begin(), d.end(), 0)) / static_cast<double>(d.size());
        std::tie(r.clusters, r.largest) = removed_clusters(d, around);
        return r;
    };
    t.all = reading(defined);
    t.majority =
        reading(compatible_directions(field.v_e, around, {0.5, IncompatibilityRule::majority}));
    t.any = reading(
        compatible_directions(field.v_e, around, {0.5, IncompatibilityRule::any_neighbour}));
    return t;
}

void bench_sizes(const std::vector<PaperRow>& rows) {
    std::printf(
        "Vector-field stage on Loop-like plates of the paper's sizes (seconds; paper: "
        "i7-9750H, 6 cores)\n\n");
    std::printf("%-7s %7s | %6s %6s %6s %6s | %7s %8s %7s | %7s %7s %6s | %7s\n", "paper", "tets",
                "fea", "vtk MB", "read", "princ.", "MST", "paper", "ratio", "removal", "paper",
                "ratio", "p+r");
    for (const PaperRow& row : rows) {
        const TetMesh mesh = loop_like_plate(row.tets);
        Stopwatch clock;
        const FeaResult fea = solve_linear_elastic(mesh, end_load(mesh));
        const double fea_s = clock.lap();

        const std::string path = (std::filesystem::temp_directory_path() /
                                  ("fibrecell-bench-" + std::to_string(row.tets) + ".vtk"))
                                     .string();
        fibrecell::config::write_file_durably(
            path, field_vtk_text(mesh, {.stress = &fea.stress}, VtkEncoding::ascii));
        const double mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
        clock.lap();
        const VolumeModel back = read_volume_model(path);
        const double read_s = clock.lap();
        std::filesystem::remove(path);

        const FieldTimes t = run_field(back.mesh, *back.stress);
        std::printf(
            "%-7s %7zu | %6.3f %6.1f %6.3f %6.3f | %7.4f %8.3f %6.0fx | %7.4f %7.3f %5.0fx | "
            "%7.4f\n",
            row.model, mesh.tet_count(), fea_s, mb, read_s, t.principal, t.mst, row.mst_s,
            row.mst_s / t.mst, t.removal, row.removal_s, row.removal_s / t.removal,
            t.principal + t.removal);
    }
}

void bench_reference(const std::string& dir) {
    std::printf("\nReference data (%s): read and Eq. 2 removal fractions\n\n", dir.c_str());
    std::printf(
        "Eq. 2 readings: fraction undefined, clusters of vertex-sharing undefined elements "
        "(largest)\n\n");
    std::printf("%-10s %7s | %6s %6s %7s %7s | %-24s | %-24s | %-24s\n", "model", "tets", "read",
                "princ.", "MST", "removal", "all (as written)", "majority", "any");
    for (const char* name : {"bunnyhead", "YogaNew"}) {
        const std::string base = fibrecell::test::reference_fea_stem(name, dir);
        if (const std::string missing = fibrecell::test::reference_fea_missing(name, dir);
            !missing.empty()) {
            std::printf("%-10s skipped: %s\n", name, missing.c_str());
            continue;
        }
        Stopwatch clock;
        const VolumeModel m = read_volume_model(base + ".tet", base + "_stress.txt");
        const double read_s = clock.lap();
        const FieldTimes t = run_field(m.mesh, *m.stress);
        auto cell = [](const FieldTimes::Reading& r) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%6.2f%% %5d (%5d)", 100 * r.fraction, r.clusters,
                          r.largest);
            return std::string(buf);
        };
        std::printf("%-10s %7zu | %6.3f %6.3f %7.4f %7.4f | %-24s | %-24s | %-24s\n", name,
                    m.mesh.tet_count(), read_s, t.principal, t.mst, t.removal, cell(t.all).c_str(),
                    cell(t.majority).c_str(), cell(t.any).c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::string reference = fibrecell::test::reference_fea_dir().string();
    int tets = 0;
    for (int i = 1; i + 1 < argc; ++i) {
        if (std::string(argv[i]) == "--reference") reference = argv[i + 1];
        if (std::string(argv[i]) == "--tets") tets = std::atoi(argv[i + 1]);
    }
    if (tets > 0) {
        bench_sizes({{"--tets", tets, 0, 0}});
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        std::printf("\npeak memory (max RSS) %.0f MB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
        return 0;
    }
    bench_sizes(std::vector<PaperRow>(std::begin(kPaper), std::end(kPaper)));
    bench_reference(reference);
    return 0;
}
