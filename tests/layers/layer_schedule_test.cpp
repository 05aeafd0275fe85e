#include "planner/layers/layer_schedule.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace fibrecell::planner;

namespace {

LayerScheduleSpec pla_only(double pla_h) {
    LayerScheduleSpec spec;
    spec.pla_layer_height_mm = pla_h;
    spec.ccf_on_all = false;
    return spec;
}

}  // namespace

TEST(LayerSchedule, PlaOnlyStackMatchesThePartAndIsCutAtMidHeights) {
    const auto layers = layer_schedule(4.0, pla_only(1.0));
    ASSERT_EQ(layers.size(), 4u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(layers[i].index, i);
        EXPECT_EQ(layers[i].head, Head::pla);
        EXPECT_EQ(layers[i].pla_number, i + 1);
        EXPECT_DOUBLE_EQ(layers[i].thickness, 1.0);
        EXPECT_DOUBLE_EQ(layers[i].z, i + 1.0);
        EXPECT_DOUBLE_EQ(layers[i].slice_z, i + 0.5);
    }
}

TEST(LayerSchedule, CcfOnEveryLayerScalesTheStackOntoThePart) {
    // H = 2, 0.8 + 0.05: round(2.5) = 3 PLA layers, stack 3 * 0.85 = 2.55, model = printed *
    // 2/2.55.
    LayerScheduleSpec spec;  // ccf_on_all by default
    const auto layers = layer_schedule(2.0, spec);
    ASSERT_EQ(layers.size(), 6u);
    const double s = 2.0 / 2.55;
    const double z[6] = {0.8, 0.85, 1.65, 1.70, 2.50, 2.55};
    const double slice[6] = {0.4 * s, 0.8 * s, 1.25 * s, 1.65 * s, 2.10 * s, 2.50 * s};
    for (int i = 0; i < 6; ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(layers[i].index, i);
        EXPECT_EQ(layers[i].head, i % 2 == 0 ? Head::pla : Head::ccf);
        EXPECT_EQ(layers[i].pla_number, i / 2 + 1);
        EXPECT_DOUBLE_EQ(layers[i].thickness, i % 2 == 0 ? 0.8 : 0.05);
        EXPECT_NEAR(layers[i].z, z[i], 1e-12);
        EXPECT_NEAR(layers[i].slice_z, slice[i], 1e-12);
    }
}

TEST(LayerSchedule, ExplicitListAndEveryNth) {
    LayerScheduleSpec spec = pla_only(1.0);
    spec.ccf_after_pla = {2};
    spec.ccf_layer_height_mm = 0.5;
    auto layers = layer_schedule(3.0, spec);  // P1 P2 C2 P3, stack 3.5
    ASSERT_EQ(layers.size(), 4u);
    EXPECT_EQ(layers[2].head, Head::ccf);
    EXPECT_EQ(layers[2].pla_number, 2);
    EXPECT_DOUBLE_EQ(layers[2].z, 2.5);
    EXPECT_DOUBLE_EQ(layers[3].z, 3.5);
    EXPECT_NEAR(layers[2].slice_z, 2.0 * 3.0 / 3.5, 1e-12);
    EXPECT_NEAR(layers[3].slice_z, 3.0 * 3.0 / 3.5, 1e-12);

    spec.ccf_after_pla.clear();
    spec.ccf_every = 2;
    spec.ccf_first = 1;
    layers = layer_schedule(5.0, spec);  // CCF after 1, 3, 5
    int ccf = 0;
    for (const auto& l : layers)
        if (l.head == Head::ccf) {
            EXPECT_EQ(l.pla_number % 2, 1);
            ++ccf;
        }
    EXPECT_EQ(ccf, 3);
}

TEST(LayerSchedule, ThinPartGetsOneLayerAndTheLastCcfCutStaysInsideThePart) {
    LayerScheduleSpec spec;
    spec.ccf_layer_height_mm = 1e-7;  // the CCF cut would land on the very top without the clamp
    const auto layers = layer_schedule(0.3, spec);
    ASSERT_EQ(layers.size(), 2u);
    const double scale = 0.3 / (0.8 + 1e-7);
    EXPECT_NEAR(layers[0].slice_z, 0.4 * scale, 1e-12);
    EXPECT_LT(layers[1].slice_z, 0.3);
    EXPECT_NEAR(layers[1].slice_z, 0.3 - 1e-3 * 0.8 * scale, 1e-12);
}

TEST(LayerSchedule, RejectsBadNumbers) {
    EXPECT_THROW(layer_schedule(0.0, LayerScheduleSpec{}), std::invalid_argument);
    EXPECT_THROW(layer_schedule(NAN, LayerScheduleSpec{}), std::invalid_argument);
    EXPECT_THROW(layer_schedule(10.0, pla_only(-1.0)), std::invalid_argument);
    EXPECT_THROW(layer_schedule(1e9, pla_only(1e-3)), std::invalid_argument);
    LayerScheduleSpec spec;
    spec.ccf_layer_height_mm = 0;
    EXPECT_THROW(layer_schedule(10.0, spec), std::invalid_argument);
    try {
        layer_schedule(10.0, pla_only(INFINITY));
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("pla_layer_height_mm"), std::string::npos);
    }
}
