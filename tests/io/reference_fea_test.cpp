// The two reference data sets (the shared folder's data/reference-fea, not in the repository):
// real Abaqus stress fields on real meshes, read end to end. Skipped when the data is missing.

#include "planner/io/read_model.hpp"

#include "io_test_support.hpp"
#include "tests/support/shared_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace fibrecell::planner;

namespace {

struct Reference {
    std::string name;
    std::size_t vertices;
    std::size_t tets;
    Eigen::Vector3d min, max;  // [mm], as the data's README gives them (2 decimals)
};

// The six components of the first stress line, parsed independently of the reader.
StressTensor first_line_stress(const std::string& path) {
    const std::string text = io_test::read_text(path);
    const std::string line = text.substr(0, text.find('\n'));
    std::vector<double> f;
    for (std::size_t at = 0; at <= line.size();) {
        const std::size_t comma = std::min(line.find(',', at), line.size());
        f.push_back(std::stod(line.substr(at, comma - at)));
        at = comma + 1;
    }
    EXPECT_EQ(f.size(), 8u);
    StressTensor s;  // elemId,P,S11,S22,S33,S12,S13,S23
    s << f[2], f[5], f[6], f[5], f[3], f[7], f[6], f[7], f[4];
    return s;
}

class ReferenceFea : public ::testing::TestWithParam<Reference> {};

}  // namespace

TEST_P(ReferenceFea, ReadsMeshStressAndSelection) {
    const Reference& r = GetParam();
    FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA(r.name);
    const std::string base = fibrecell::test::reference_fea_stem(r.name);
    const VolumeModel m = read_volume_model(base + ".tet", base + "_stress.txt");

    EXPECT_EQ(m.mesh.vertex_count(), r.vertices);
    EXPECT_EQ(m.mesh.tet_count(), r.tets);
    Eigen::Vector3d lo = m.mesh.vertices.front(), hi = lo;
    for (const auto& v : m.mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(lo[k], r.min[k], 0.01) << "min " << k;
        EXPECT_NEAR(hi[k], r.max[k], 0.01) << "max " << k;
    }
    ASSERT_TRUE(m.stress);
    ASSERT_EQ(m.stress->size(), r.tets);
    EXPECT_EQ(m.stress->front(), first_line_stress(base + "_stress.txt"));
    EXPECT_FALSE(m.vertex_groups.at("fixed").empty());
    EXPECT_FALSE(m.vertex_groups.at("handle").empty());
    EXPECT_TRUE(io_test::all_positive(m.mesh)) << "the README says the tets are positive";
}

INSTANTIATE_TEST_SUITE_P(
    Data, ReferenceFea,
    ::testing::Values(
        Reference{"bunnyhead", 12000, 60375, {-104.48, -6.57, -39.84}, {17.56, 79.53, 41.61}},
        Reference{"YogaNew", 11000, 52446, {-49.54, 1.80, -24.89}, {53.84, 147.01, 24.03}}),
    [](const auto& test) { return test.param.name; });
