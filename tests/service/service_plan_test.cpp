// One plan, one truth, with fibrecelld as its users run it: what prints is the plan directory as
// planned, checked against its manifest with the system's sha256sum; a plan for a cell that has
// changed is refused until it is replanned; a damaged one is refused; a service killed while it
// writes a plan never leaves a planned job with a bad file; and the job's settings reach the
// board (its own log of what it ran) and the robot (the RAPID speed data).
#include "external_cell.hpp"
#include "service_fixture.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <thread>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::HasSubstr;

namespace {

fs::path plan_dir(const fs::path& state, std::int64_t id) {
    return state / "jobs" / std::to_string(id) / "plan";
}

// The plan's files against its manifest, by sha256sum (not the service's own check).
bool plan_verifies(const fs::path& plan, std::string& why) {
    const std::string text = read_file(plan / "manifest.json");
    const json m = json::parse(text, nullptr, false);
    if (m.is_discarded() || !m.contains("files")) {
        why = "no readable manifest.json: " + text;
        return false;
    }
    std::ofstream list(plan / ".." / "sums.txt");
    for (const json& f : m["files"]) list << f.value("sha256", "") << "  " << f.value("path", "") << "\n";
    list.close();
    const std::string cmd = "cd " + plan.string() + " && sha256sum --quiet -c ../sums.txt > ../sums.out 2>&1";
    if (std::system(cmd.c_str()) != 0) {
        why = read_file(plan / ".." / "sums.out");
        return false;
    }
    return true;
}

std::string state_on_disk(const fs::path& state, std::int64_t id) {
    const json s = json::parse(read_file(state / "jobs" / std::to_string(id) / "state.json"), nullptr, false);
    return s.is_discarded() ? "" : s.value("state", "");
}

}  // namespace

TEST_F(ServiceTest, APlanForACellThatChangedIsRefusedUntilItIsReplanned) {
    start_service(write_config());
    std::int64_t id = 0;
    {
        auto c = client();
        id = submit_bar(c, false);
        ASSERT_EQ(wait_for_state(c, id, "planned").value("state", ""), "planned");
    }
    ASSERT_TRUE(service_->terminate(20s));
    // The bed was moved 10 mm: every target of the plan is 10 mm off on this cell.
    start_service(write_config("robot: {bed: {position_mm: [390, -150, 100]}}\n"));
    auto c = client();
    EXPECT_EQ(c.call("job.start", {{"job", id}}).value("state", ""), "starting");
    const json refused = wait_for_state(c, id, "planned");
    ASSERT_EQ(refused.value("state", ""), "planned") << refused.dump(2);
    EXPECT_THAT(refused.value("reason", ""),
                HasSubstr("the cell changed since the job was planned (robot.bed.position_mm: "
                          "[380.0,-150.0,100.0] when planned, [390.0,-150.0,100.0] now); replan "
                          "the job to print it on this cell"));
    EXPECT_FALSE(refused.contains("result"));  // nothing ran
    // Replanned, by the CLI as an operator would, it prints.
    const std::string cmd = fibrecell::test::binary_path("tools/fibrecell replan ") +
                            std::to_string(id) + " --socket " + socket().string() + " > " +
                            (dir_ / "replan.out").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_file(dir_ / "replan.out");
    EXPECT_THAT(read_file(dir_ / "replan.out"), HasSubstr("job " + std::to_string(id) + ": planning"));
    ASSERT_EQ(wait_for_state(c, id, "planned").value("state", ""), "planned");
    const json manifest = json::parse(read_file(plan_dir(state_dir(), id) / "manifest.json"));
    EXPECT_EQ(manifest["cell"]["robot"]["bed"]["position_mm"], json::array({390.0, -150.0, 100.0}));
    c.call("job.start", {{"job", id}});
    const json done = wait_for_state(c, id, "completed", 120s);
    EXPECT_TRUE(printed(done)) << done.dump(2) << service_->log();
    // A job that is printing or done cannot be replanned.
    try {
        c.call("job.replan", {{"job", id}});
        ADD_FAILURE() << "a completed job was replanned";
    } catch (const api::ApiCallError& e) {
        EXPECT_THAT(e.what(), HasSubstr("it has ended"));
    }
}

TEST_F(ServiceTest, ADamagedPlanIsRefusedNamingTheFile) {
    start_service(write_config());
    auto c = client();
    const std::int64_t id = submit_bar(c, false);
    ASSERT_EQ(wait_for_state(c, id, "planned").value("state", ""), "planned");
    const fs::path chunk = plan_dir(state_dir(), id) / "rapid" / "FcChunk0001.mod";
    std::string text = read_file(chunk);
    ASSERT_FALSE(text.empty());
    text.resize(text.size() - 10);  // a write cut short by a power loss
    std::ofstream(chunk, std::ios::binary | std::ios::trunc) << text;
    c.call("job.start", {{"job", id}});
    const json refused = wait_for_state(c, id, "planned");
    EXPECT_THAT(refused.value("reason", ""),
                HasSubstr("the plan is damaged (rapid/FcChunk0001.mod: "));
    EXPECT_THAT(refused.value("reason", ""), HasSubstr("replan the job"));
}

TEST_F(ServiceTest, KilledWhileWritingAPlanNeverLeavesAPlannedJobWithABadFile) {
    // Killed the moment a plan file appears (the field file first, a RAPID chunk, the manifest
    // last): the job on the disk is still planning, or planned with every file as its manifest
    // says; after the restart it ends planned with a plan that verifies.
    for (const char* file : {"field.vtk", "rapid/FcChunk0001.mod", "manifest.json"}) {
        SCOPED_TRACE(file);
        start_service(write_config());
        std::int64_t id = 0;
        {
            auto c = client();
            id = submit_bar(c, false);
        }
        const fs::path target = plan_dir(state_dir(), id) / file;
        const auto end = std::chrono::steady_clock::now() + 60s;
        while (!fs::exists(target) && std::chrono::steady_clock::now() < end)
            std::this_thread::yield();  // a stat per turn: the kill lands within microseconds
        ASSERT_TRUE(fs::exists(target));
        service_->kill_now();
        const std::string on_disk = state_on_disk(state_dir(), id);
        std::string why;
        if (on_disk == "planned") EXPECT_TRUE(plan_verifies(plan_dir(state_dir(), id), why)) << why;
        else EXPECT_EQ(on_disk, "planning");
        start_service(write_config());
        auto c = client();
        const json planned = wait_for_state(c, id, "planned");
        ASSERT_EQ(planned.value("state", ""), "planned") << planned.dump(2);
        EXPECT_TRUE(plan_verifies(plan_dir(state_dir(), id), why)) << why;
        ASSERT_TRUE(service_->terminate(20s));
    }
}

TEST_F(ServiceTest, TheJobsSettingsReachTheBoardAndTheRobot) {
    constexpr double time_scale = 50;
    ExternalCell devices(dir_, time_scale);
    ASSERT_TRUE(devices.up());
    std::ofstream(dir_ / "cell.yaml") << devices.cell_yaml(read_file(write_config("", time_scale)));
    std::ofstream(dir_ / "jobs/bar.job.yaml")
        << "name: bar\nmodel:\n  mesh: bar.vtk\nplacement:\n  position_mm: [150, 150]\n"
           "process:\n"
           "  pla: {nozzle_temp_c: 215, travel_speed_mm_s: 80, line_width_mm: 0.6}\n"
           "  ccf: {nozzle_temp_c: 245, travel_speed_mm_s: 90}\n";
    start_service(dir_ / "cell.yaml");
    auto c = client();
    const std::int64_t id = submit_bar(c, true);
    const json done = wait_for_state(c, id, "completed", 180s);
    ASSERT_TRUE(printed(done)) << done.dump(2) << service_->log();

    // The board ran the job's temperatures (pre-flight heat-up: M104 both, then M109 both).
    const std::string log = read_file(devices.board_log());
    for (const char* line : {"M104 T0 S215", "M104 T1 S245", "M109 T0 S215", "M109 T1 S245"})
        EXPECT_THAT(log, HasSubstr(line));
    EXPECT_THAT(log, ::testing::Not(HasSubstr(" S200")));  // not the cell's old defaults
    EXPECT_THAT(log, ::testing::Not(HasSubstr(" S250")));
    // The PLA flow of a 0.6 mm line on 0.8 mm layers from 1.75 mm filament: the metered feed at
    // 12 mm/s of path runs at 12 * 0.6 * 0.8 / (pi 1.75^2 / 4) mm/s of filament (F per minute).
    const auto feed = [](double line_width_mm) {
        char f[32];
        std::snprintf(f, sizeof f, " F%.1f\n",
                      12 * line_width_mm * 0.8 / (std::numbers::pi * 1.75 * 1.75 / 4) * 60);
        return std::string(f);
    };
    EXPECT_THAT(log, HasSubstr(feed(0.6)));
    EXPECT_THAT(log, ::testing::Not(HasSubstr(feed(0.8))));  // the job default's

    // The robot: the RAPID speed data for travel are the job's, per nozzle.
    std::string rapid;
    for (const auto& e : fs::directory_iterator(plan_dir(state_dir(), id) / "rapid")) rapid += read_file(e.path());
    EXPECT_THAT(rapid, ::testing::ContainsRegex("speeddata vFcTravel[_0-9]* := \\[80,"));
    EXPECT_THAT(rapid, ::testing::ContainsRegex("speeddata vFcTravel[_0-9]* := \\[90,"));
    EXPECT_THAT(rapid, ::testing::Not(HasSubstr(":= [100,")));  // the job default's
}

TEST_F(ServiceTest, ASettingTheCellCannotPrintRefusesTheSubmitAndStoresNothing) {
    start_service(write_config());
    auto c = client();
    std::ofstream(dir_ / "jobs/hot.job.yaml")
        << "name: hot\nmodel:\n  mesh: bar.vtk\nplanner: {cutter_distance_mm: 35}\n";
    try {
        c.call("job.submit", submit_params(dir_ / "jobs/hot.job.yaml", "bar.vtk", false), 30s);
        ADD_FAILURE() << "submitted";
    } catch (const api::ApiCallError& e) {
        EXPECT_THAT(e.what(), HasSubstr("planner.cutter_distance_mm: 35 mm, but the cell's cutter "
                                        "sits 42 mm before the nozzle tip"));
    }
    EXPECT_TRUE(c.call("job.list", json::object()).empty());
}

// One tetrahedron a kilometre wide, a file of a few hundred bytes: refused before any planning
// work, with the figures, while a part the cell can print behind it plans as usual.
TEST_F(ServiceTest, APartLargerThanTheCellIsRefusedBeforeAnyPlanningWork) {
    planner::TetMesh huge;
    huge.vertices = {{0, 0, 0}, {1e6, 0, 0}, {0, 1e6, 0}, {0, 0, 1e6}};
    huge.tets = {{0, 1, 2, 3}};
    std::vector<planner::StressTensor> stress(1, planner::StressTensor::Identity());
    fibrecell::test::write_vtk_file(dir_ / "jobs/huge.vtk", huge, {.stress = &stress});
    std::ofstream(dir_ / "jobs/huge.job.yaml") << "name: huge\nmodel:\n  mesh: huge.vtk\n";
    EXPECT_LT(fs::file_size(dir_ / "jobs/huge.vtk"), 1000u);

    start_service(write_config());
    auto c = client();
    const auto t0 = std::chrono::steady_clock::now();
    const std::int64_t id =
        c.call("job.submit", submit_params(dir_ / "jobs/huge.job.yaml", "huge.vtk", false), 30s)
            .value("id", std::int64_t{0});
    const json failed = wait_for_state(c, id, "failed", 30s);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(failed.value("state", ""), "failed") << failed.dump(2);
    EXPECT_THAT(failed.value("reason", ""),
                HasSubstr("the part as placed is 1000000.0 x 1000000.0 x 1000000.0 mm (x, y, z); this "
                          "cell takes at most 400 x 400 x 300 mm (part_limits.max_size_mm)"));
    std::printf("refused in %.3f s: %s\n", seconds, failed.value("reason", "").c_str());
    EXPECT_LT(seconds, 5.0);  // generous (ASan, a loaded machine); it takes milliseconds

    // Within the size limit but out of the robot's reach: the bar placed 2 m away.
    std::ofstream(dir_ / "jobs/far.job.yaml")
        << "name: far\nmodel:\n  mesh: bar.vtk\nplacement:\n  position_mm: [2000, 150]\n";
    const std::int64_t far =
        c.call("job.submit", submit_params(dir_ / "jobs/far.job.yaml", "bar.vtk", false), 30s)
            .value("id", std::int64_t{0});
    const json far_failed = wait_for_state(c, far, "failed", 30s);
    EXPECT_THAT(far_failed.value("reason", ""), HasSubstr("out of the robot's reach"));

    const std::int64_t bar = submit_bar(c, false);
    EXPECT_EQ(wait_for_state(c, bar, "planned", 120s).value("state", ""), "planned");
}

// A stop while a job plans: the service waits for planning only jobs.stop_grace_s (here 0, so a
// plan is always caught inside a step; the default is 10 s, within systemd's 30 s stop timeout),
// then exits, saying so, with the devices stopped as usual. The job plans again at the next start.
TEST_F(ServiceTest, AStopDoesNotWaitForPlanningPastItsGraceAndTheJobPlansAtTheNextStart) {
    fs::copy(fibrecell::test::source_path("examples/loop"), dir_ / "loop");
    std::string text = read_file(write_config());
    const std::string from = "jobs: {planner_threads: 1}";
    text.replace(text.find(from), from.size(), "jobs: {planner_threads: 1, stop_grace_s: 0}");
    std::ofstream(dir_ / "cell.yaml") << text;
    start_service(dir_ / "cell.yaml");
    std::int64_t id = 0;
    {
        auto c = client();
        id = c.call("job.submit", submit_params(dir_ / "loop/loop.job.yaml", "loop.msh", false), 30s)
                 .value("id", std::int64_t{0});
        ASSERT_TRUE(eventually([&] {
            const json j = c.call("job.get", {{"job", id}});
            const std::string stage = j.contains("planning") ? j["planning"].value("stage", "") : "";
            return !stage.empty() && stage != "queued" && stage != "read";
        }, 60s, 20ms)) << service_->log();
    }
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_TRUE(service_->terminate(20s)) << service_->log();
    const double stop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("stopped in %.3f s while planning\n", stop_s);
    EXPECT_LT(stop_s, 5.0);  // it takes milliseconds; generous for ASan on a loaded machine
    EXPECT_THAT(service_->log(), HasSubstr("service.stop_unfinished planning of job " + std::to_string(id) + " (stage "));
    EXPECT_EQ(state_on_disk(state_dir(), id), "planning");

    // Planned again from the start (the whole Loop takes minutes under ASan on a loaded machine:
    // its planning beginning is the event this test means).
    start_service(write_config());
    ASSERT_TRUE(service_->wait_for_log("job.planning job " + std::to_string(id), 60s)) << service_->log();
    auto c = client();
    EXPECT_EQ(c.call("job.get", {{"job", id}}).value("state", ""), "planning");
}

// Memory: what a plan takes is bounded before it is allocated (part_limits; docs/service.md,
// "Memory"), and a machine that still cannot give it fails that job alone. Shown on the running
// service with its address space capped (prlimit on its pid) just above what it uses idle: the
// FEA of a 30k-tet bar needs more, the job fails saying so, and the next job plans. Release
// builds only: ASan reserves terabytes of address space and cannot run under such a cap
// (.ci/run runs this test in its Release build).
TEST_F(ServiceTest, APlanThatRunsOutOfMemoryFailsAloneAndTheServiceGoesOn) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "address-space limits do not work under AddressSanitizer";
#else
    const auto mesh = planner::structured_tet_mesh({.size = {100, 20, 10}, .cells = {50, 10, 10}});
    fibrecell::test::write_vtk_file(dir_ / "jobs/big.vtk", mesh, {});
    std::ofstream(dir_ / "jobs/big.job.yaml")
        << "name: big\nmodel:\n  mesh: big.vtk\n  load_case:\n"
           "    material: {youngs_modulus_mpa: 3500, poisson_ratio: 0.36}\n"
           "    supports: [left]\n    loads:\n      - {region: right, force_n: [1000, 0, 0]}\n"
           "regions:\n  left: {box: {min: [-0.1, -1, -1], max: [0.1, 21, 11]}}\n"
           "  right: {box: {min: [99.9, -1, -1], max: [100.1, 21, 11]}}\n"
           "placement:\n  position_mm: [150, 150]\n";
    start_service(write_config());
    const pid_t pid = service_->pid();
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    long vm_kb = 0;
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmSize:", 0) == 0) vm_kb = std::stol(line.substr(7));
    ASSERT_GT(vm_kb, 0);
    const rlimit cap{.rlim_cur = static_cast<rlim_t>(vm_kb + 64 * 1024) * 1024,
                     .rlim_max = static_cast<rlim_t>(vm_kb + 64 * 1024) * 1024};
    ASSERT_EQ(::prlimit(pid, RLIMIT_AS, &cap, nullptr), 0);
    auto c = client();
    const std::int64_t big =
        c.call("job.submit", submit_params(dir_ / "jobs/big.job.yaml", "big.vtk", false), 30s)
            .value("id", std::int64_t{0});
    const json failed = wait_for_state(c, big, "failed", 120s);
    ASSERT_EQ(failed.value("state", ""), "failed") << failed.dump(2) << service_->log();
    // Where it ran out decides the words: the factorisation (CHOLMOD's own allocation) or any
    // other step (std::bad_alloc).
    EXPECT_THAT(failed.value("reason", ""), HasSubstr("out of memory"));
    std::printf("failed: %s\n", failed.value("reason", "").c_str());
    const std::int64_t bar = submit_bar(c, false);
    EXPECT_EQ(wait_for_state(c, bar, "planned", 120s).value("state", ""), "planned") << service_->log();
    EXPECT_TRUE(service_->running());
#endif
}

// An abort while a large layer is planned (a 400 x 400 mm plate, the widest part the limits
// accept: seconds per CCF layer) stops the planner within the bound docs/service.md states
// (tens of milliseconds in Release; 1 s allowed here, under ASan on a loaded machine). Measured
// from the abort's answer to the worker's own log line, job.plan_cancelled.
TEST_F(ServiceTest, AnAbortStopsTheLayersOfTheWidestPartWithinASecond) {
    std::ofstream(dir_ / "jobs/plate.vtk")
        << "# vtk DataFile Version 3.0\nplate\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n"
           "0 0 0\n400 0 0\n400 400 0\n0 400 0\n0 0 1.6\n400 0 1.6\n400 400 1.6\n0 400 1.6\n"
           "CELLS 5 25\n4 0 1 3 4\n4 1 2 3 6\n4 1 4 5 6\n4 3 4 6 7\n4 1 3 4 6\n"
           "CELL_TYPES 5\n10\n10\n10\n10\n10\nCELL_DATA 5\nTENSORS stress double\n"
        << [] {
               std::string t;
               for (int i = 0; i < 5; ++i) t += "20 0 0\n0 0 0\n0 0 0\n";
               return t;
           }();
    std::ofstream(dir_ / "jobs/plate.job.yaml")
        << "name: plate\nmodel:\n  mesh: plate.vtk\nplacement:\n  position_mm: [0, 0]\n";
    start_service(write_config());
    auto c = client();
    const std::int64_t id =
        c.call("job.submit", submit_params(dir_ / "jobs/plate.job.yaml", "plate.vtk", false), 30s)
            .value("id", std::int64_t{0});
    // Into the first CCF layer: the PLA layer below it is done (a quarter of the four layers).
    ASSERT_TRUE(eventually([&] {
        const json j = c.call("job.get", {{"job", id}});
        return j.contains("planning") && j["planning"].value("stage", "") == "layers" &&
               j["planning"].value("fraction", 0.0) >= 0.25;
    }, 60s, 10ms)) << service_->log();
    const auto aborted_at = std::chrono::system_clock::now();
    EXPECT_EQ(c.call("job.abort", {{"job", id}}).value("state", ""), "aborted");
    ASSERT_TRUE(service_->wait_for_log("job.plan_cancelled job " + std::to_string(id), 60s)) << service_->log();
    const auto stopped_at = fibrecell::test::logged_at(service_->log(), "job.plan_cancelled job");
    ASSERT_TRUE(stopped_at);
    const double ms = std::chrono::duration<double, std::milli>(*stopped_at - aborted_at).count();
    std::printf("abort -> planning stopped: %.0f ms\n", ms);
    EXPECT_LT(ms, 1000);
}
