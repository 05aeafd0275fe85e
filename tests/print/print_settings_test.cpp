// The one mapping from a job and a cell to the print's settings: every job setting takes effect
// (it reaches the program options and the sync options, what the RAPID speed data and the board
// commands are made from) or the job is refused with a message naming the job's key, the cell's
// key and both values.
#include "daemon/print/print_settings.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace fibrecell;
using daemon::CellConfig;
using daemon::print::PrintSettings;
using daemon::print::SettingsError;
using daemon::print::print_settings;

namespace {

planner::JobSpec job_with(const std::string& yaml) {
    return planner::parse_job("name: j\nmodel:\n  mesh: loop.msh\n" + yaml, "j.job.yaml",
                              fibrecell::test::source_path("examples/loop"), planner::JobFiles::anywhere);
}

std::string refusal(const planner::JobSpec& job, const CellConfig& cell = {}) {
    try {
        print_settings(job, cell);
    } catch (const SettingsError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(PrintSettings, EveryJobSettingReachesWhatThePrintIsMadeFrom) {
    const planner::JobSpec job = job_with(
        "layers: {pla_layer_height_mm: 0.6}\n"
        "process:\n"
        "  pla: {speed_mm_s: 14, travel_speed_mm_s: 80, nozzle_temp_c: 215, line_width_mm: 0.7}\n"
        "  ccf: {speed_mm_s: 4, travel_speed_mm_s: 90, nozzle_temp_c: 245, line_width_mm: 1.1}\n");
    const PrintSettings s = print_settings(job, CellConfig{});
    const drivers::abb::ProgramOptions p = s.program_options();
    EXPECT_EQ(p.pla_speed_mm_s, 14);
    EXPECT_EQ(p.ccf_speed_mm_s, 4);
    EXPECT_EQ(p.pla_travel_speed_mm_s, 80);
    EXPECT_EQ(p.ccf_travel_speed_mm_s, 90);
    EXPECT_EQ(p.cutter_distance_mm, 42);  // the cell's
    daemon::sync::SyncOptions o;
    s.apply_to(o);
    EXPECT_EQ(o.hotends.pla_c, 215);
    EXPECT_EQ(o.hotends.ccf_c, 245);
    EXPECT_EQ(o.pla_line_width_mm, 0.7);
    EXPECT_EQ(o.pla_layer_height_mm, 0.6);
    EXPECT_EQ(s.pla.nozzle_diameter_mm, 0.8);  // the cell's mounted nozzles
    EXPECT_EQ(s.ccf.nozzle_diameter_mm, 1.0);
    EXPECT_EQ(s.ccf.line_width_mm, 1.1);
    // As print.json keeps them.
    const PrintSettings back = daemon::print::settings_from_json(daemon::print::to_json(s));
    EXPECT_EQ(daemon::print::to_json(back), daemon::print::to_json(s));
}

TEST(PrintSettings, TemperaturesStayInsideTheCellsLimits) {
    EXPECT_EQ(refusal(job_with("process: {pla: {nozzle_temp_c: 290}}\n")),
              "j.job.yaml: process.pla.nozzle_temp_c: 290 degC is above the cell's limit 260 degC "
              "(extruder.pla.max_temp_c)");
    EXPECT_EQ(refusal(job_with("process: {ccf: {nozzle_temp_c: 150}}\n")),
              "j.job.yaml: process.ccf.nozzle_temp_c: 150 degC is below 170 degC, where the "
              "firmware refuses to extrude (extruder.min_extrude_temp_c)");
    CellConfig hot;
    hot.extruder.ccf_max_temp_c = 300;
    EXPECT_EQ(refusal(job_with("process: {ccf: {nozzle_temp_c: 290}}\n"), hot), "");
}

TEST(PrintSettings, TravelFasterThanTheCellAllowsIsRefused) {
    EXPECT_EQ(refusal(job_with("process: {ccf: {travel_speed_mm_s: 400}}\n")),
              "j.job.yaml: process.ccf.travel_speed_mm_s: 400 mm/s is above the cell's limit 250 "
              "mm/s (robot.motion.max_travel_speed_mm_s)");
}

TEST(PrintSettings, HardwareComesFromTheCellAndAJobThatStatesOtherIsRefused) {
    EXPECT_EQ(refusal(job_with("planner: {cutter_distance_mm: 40}\n")),
              "j.job.yaml: planner.cutter_distance_mm: 40 mm, but the cell's cutter sits 42 mm "
              "before the nozzle tip (extruder.ccf.cutter_distance_mm): leave the key out, the "
              "cell's value is used");
    EXPECT_EQ(refusal(job_with("planner: {cutter_distance_mm: 42}\n")), "");
    EXPECT_EQ(refusal(job_with("process: {pla: {nozzle_diameter_mm: 0.6}}\n")),
              "j.job.yaml: process.pla.nozzle_diameter_mm: 0.6 mm, but the cell's PLA nozzle is "
              "0.8 mm (extruder.pla.nozzle_diameter_mm): change the nozzle or leave the key out");
    CellConfig other;
    other.extruder.cutter_distance_mm = 55;
    other.extruder.pla_nozzle_diameter_mm = 0.6;
    const PrintSettings s =
        print_settings(job_with("process: {pla: {nozzle_diameter_mm: 0.6}}\n"), other);
    EXPECT_EQ(s.cutter_distance_mm, 55);
    EXPECT_EQ(s.program_options().cutter_distance_mm, 55);
    EXPECT_EQ(s.pla.nozzle_diameter_mm, 0.6);
}
