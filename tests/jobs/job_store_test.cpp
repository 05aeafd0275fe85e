// The job store on a real state directory: submission, the state walk through the store, atomic
// state.json, the journal, crash recovery, the planning retry limit, a corrupt job isolated, ids
// across restarts. Nothing plans here (plan_runner_test.cpp does).
#include "daemon/jobs/job_store.hpp"

#include "config/durable_file.hpp"
#include "job_test_files.hpp"
#include "tests/support/plan_inputs.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace fibrecell;
using namespace fibrecell::daemon::jobs;
using fibrecell::config::is_leftover_temp_file;
using fibrecell::test::read_file;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

class JobStoreTest : public ::testing::Test {
  protected:
    void SetUp() override {
        // A tiny stressed box: submission checks the job file, nothing is planned.
        const auto mesh = planner::structured_tet_mesh({.size = {10, 10, 2}, .cells = {1, 1, 1}});
        std::vector<planner::StressTensor> stress(mesh.tet_count(),
                                                  planner::StressTensor::Identity());
        fibrecell::test::write_vtk_file(dir_ / "box.vtk", mesh, {.stress = &stress});
        input_.job_yaml = "name: box\nmodel:\n  mesh: box.vtk\n";
        input_.files = {{"box.vtk", read_file(dir_ / "box.vtk")}};
    }

    JobStoreOptions options() const { return {.state_dir = dir_ / "state"}; }
    fs::path state_file(std::int64_t id) const {
        return dir_ / "state" / "jobs" / std::to_string(id) / "state.json";
    }
    // Drives job `id` (planning) into `target` through the store's own transitions.
    void drive(JobStore& store, std::int64_t id, JobState target) {
        using A = JobAction;
        const auto step = [&](A a) {
            if (is_user_action(a))
                store.request(id, a);
            else
                ASSERT_TRUE(store.apply(id, a, a == A::faulted ? "board unplugged" : ""));
        };
        const std::map<JobState, std::vector<A>> paths = {
            {JobState::planning, {}},
            {JobState::planned, {A::plan_done}},
            {JobState::starting, {A::plan_done, A::start}},
            {JobState::printing, {A::plan_done, A::start, A::print_started}},
            {JobState::pausing, {A::plan_done, A::start, A::print_started, A::pause}},
            {JobState::paused, {A::plan_done, A::start, A::print_started, A::pause, A::pause_done}},
            {JobState::completed, {A::plan_done, A::start, A::print_started, A::print_done}},
            {JobState::completed_with_warnings,
             {A::plan_done, A::start, A::print_started, A::print_short}},
            {JobState::aborted, {A::abort}},
            {JobState::failed, {A::plan_failed}},
        };
        for (A a : paths.at(target)) step(a);
        ASSERT_EQ(store.get(id).state, target);
    }
    // A fresh store's first job, submitted and driven to printing.
    std::int64_t printing_job(JobStore& store) {
        store.load_all();
        const auto id = store.submit(input_).id;
        drive(store, id, JobState::printing);
        return id;
    }

    test::TempDir dir_{"jobstore"};
    JobInput input_;
};

}  // namespace

TEST_F(JobStoreTest, SubmitStoresTheInputsAndQueuesForPlanning) {
    JobStore store(options());
    store.load_all();
    std::vector<JobRecord> seen;
    store.on_change([&](const JobRecord& r) { seen.push_back(r); });
    const JobRecord r = store.submit(input_);
    EXPECT_EQ(r.id, 1);
    EXPECT_EQ(r.name, "box");
    EXPECT_EQ(r.state, JobState::planning);
    EXPECT_EQ(r.progress.stage, "queued");
    const fs::path job = dir_ / "state" / "jobs" / "1";
    EXPECT_EQ(read_file(job / "input" / "job.yaml"), input_.job_yaml);
    EXPECT_EQ(read_file(job / "input" / "box.vtk"), input_.files[0].second);
    EXPECT_TRUE(fs::is_directory(job / "plan"));
    const auto state = nlohmann::json::parse(read_file(state_file(1)));
    EXPECT_EQ(state["format"], "fibrecell.job/1");
    EXPECT_EQ(state["state"], "planning");
    EXPECT_EQ(read_file(dir_ / "state" / "next_id"), "2\n");
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].id, 1);
}

TEST_F(JobStoreTest, BadSubmissionIsRefusedAndUsesNoId) {
    JobStore store(options());
    store.load_all();
    JobInput bad = input_;
    bad.job_yaml = "name: box\nmodel:\n  mesh: box.vtk\nplanner:\n  eta: 7\n";
    try {
        store.submit(bad);
        FAIL() << "expected an error";
    } catch (const config::ConfigError& e) {
        EXPECT_THAT(e.what(),
                    HasSubstr("job.yaml: line 5: planner.eta: must be in [-1, 1], got 7"));
    }
    JobInput escape = input_;
    escape.files.push_back({"../evil.txt", "x"});
    try {
        store.submit(escape);
        FAIL() << "expected an error";
    } catch (const JobInputError& e) {
        EXPECT_STREQ(e.what(), "files[\"../evil.txt\"]: parts must not be empty, '.' or '..'");
    }
    JobInput clash = input_;
    clash.files.push_back({"box.vtk/inner.txt", "x"});
    try {
        store.submit(clash);
        FAIL() << "expected an error";
    } catch (const JobInputError& e) {
        EXPECT_STREQ(e.what(),
                     "files[\"box.vtk/inner.txt\"]: lies in \"box.vtk\", which is a file of the job");
    }
    JobInput long_part = input_;
    long_part.files.push_back({"d/" + std::string(256, 'p'), "x"});
    try {
        store.submit(long_part);
        FAIL() << "expected an error";
    } catch (const JobInputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("a part of the name is longer than 255 bytes"));
    }
    // A file of the host and a file that does not exist get the same answer: no existence oracle.
    for (const std::string& mesh : {(dir_ / "box.vtk").string(), (dir_ / "nothing.vtk").string(),
                                    std::string("nothing.vtk"), std::string("../box.vtk")}) {
        JobInput host_file = input_;
        host_file.job_yaml = "name: box\nmodel:\n  mesh: " + mesh + "\n";
        try {
            store.submit(host_file);
            FAIL() << "expected an error for " << mesh;
        } catch (const config::ConfigError& e) {
            EXPECT_THAT(e.what(), HasSubstr("job.yaml: line 3: model.mesh: must name a file "
                                            "submitted with the job, not " +
                                            mesh));
        }
    }
    EXPECT_TRUE(store.list().empty());
    EXPECT_EQ(
        std::distance(fs::directory_iterator(dir_ / "state" / "jobs"), fs::directory_iterator{}),
        0);  // no leftover folder
    EXPECT_EQ(store.submit(input_).id, 1);
}

TEST_F(JobStoreTest, QueueLimitRefusesMoreSubmissions) {
    JobStoreOptions o = options();
    o.max_queued = 2;
    JobStore store(o);
    store.load_all();
    store.submit(input_);
    store.submit(input_);
    try {
        store.submit(input_);
        FAIL() << "expected a conflict";
    } catch (const JobConflict& e) {
        EXPECT_THAT(e.what(), HasSubstr("the job queue is full (2 jobs planning or planned"));
    }
    store.request(1, JobAction::abort);
    EXPECT_EQ(store.submit(input_).id, 3);
}

TEST_F(JobStoreTest, StoreWalksEveryUserActionFromEveryState) {
    // For each state a fresh job is driven there; each user action is tried on it. An allowed one
    // lands where the table says and is on disk; a refused one changes nothing on disk either.
    JobStoreOptions o = options();
    // 50 stores and ~250 durable writes: on tmpfs, where fsync costs nothing, when there is one.
    if (fs::is_directory("/dev/shm")) o.state_dir = fs::path("/dev/shm") / dir_.path().filename();
    o.max_queued = 1000;
    o.keep_completed = 1000;
    const auto walk_state_file = [&](std::int64_t id) {
        return o.state_dir / "jobs" / std::to_string(id) / "state.json";
    };
    for (JobState s : all_job_states) {
        for (JobAction a : user_actions) {
            fs::remove_all(o.state_dir);  // one job alone: no other job holds the cell
            std::optional<JobStore> reopened(std::in_place, o);
            reopened->load_all();
            const std::int64_t id = reopened->submit(input_).id;
            if (s == JobState::interrupted) {  // only a restart leads there
                drive(*reopened, id, JobState::printing);
                reopened->journal(id);  // as the print runner opens it before the print starts
                reopened.emplace(o);
                reopened->load_all();
            } else {
                drive(*reopened, id, s);
            }
            JobStore& store = *reopened;
            ASSERT_EQ(store.get(id).state, s);
            const std::string before = read_file(walk_state_file(id));
            const std::string refused = refusal(id, s, a);
            SCOPED_TRACE(std::string(to_string(s)) + " + " + std::string(to_string(a)));
            if (refused.empty()) {
                const JobRecord r = store.request(id, a);
                if (a == JobAction::remove) {
                    EXPECT_FALSE(fs::exists(walk_state_file(id).parent_path()));
                    EXPECT_THROW(store.get(id), JobNotFound);
                } else {
                    EXPECT_EQ(r.state, allowed_targets(s, a).front());
                    const auto disk = nlohmann::json::parse(read_file(walk_state_file(id)));
                    EXPECT_EQ(disk["state"], std::string(to_string(r.state)));
                }
            } else {
                try {
                    store.request(id, a);
                    ADD_FAILURE() << "expected a conflict";
                } catch (const JobConflict& e) {
                    EXPECT_EQ(e.what(), refused);
                }
                EXPECT_EQ(read_file(walk_state_file(id)), before);
                EXPECT_EQ(store.get(id).state, s);
            }
        }
    }
    fs::remove_all(o.state_dir);
}

TEST_F(JobStoreTest, RefusalsNameTheJobAndWhatToDo) {
    JobStore store(options());
    const auto id = printing_job(store);
    try {
        store.request(id, JobAction::remove);
        FAIL();
    } catch (const JobConflict& e) {
        EXPECT_STREQ(e.what(), "job 1 is printing: pause or abort it first");
    }
    // One job prints at a time: another planned job may not start.
    const auto other = store.submit(input_).id;
    drive(store, other, JobState::planned);
    try {
        store.request(other, JobAction::start);
        FAIL();
    } catch (const JobConflict& e) {
        EXPECT_STREQ(e.what(),
                     "job 1 is printing: one job prints at a time: wait until it ends or abort it");
    }
    store.request(id, JobAction::pause);
    store.apply(id, JobAction::pause_done);
    try {
        store.request(other, JobAction::start);
        FAIL();
    } catch (const JobConflict& e) {
        EXPECT_STREQ(e.what(), "job 1 is paused: its part is on the bed: resume or abort it first");
    }
    EXPECT_THROW(store.request(99, JobAction::start), JobNotFound);
    // A service event that no longer fits (the job was aborted meanwhile) changes nothing.
    store.request(other, JobAction::abort);
    EXPECT_FALSE(store.apply(other, JobAction::print_started));
    EXPECT_EQ(store.get(other).state, JobState::aborted);
    EXPECT_EQ(store.get(other).reason, "aborted by the operator");
}

TEST_F(JobStoreTest, StartRefusedGoesBackWhereItCameFrom) {
    {
        JobStore store(options());
        store.load_all();
        const auto id = store.submit(input_).id;
        drive(store, id, JobState::starting);
        ASSERT_TRUE(store.apply(id, JobAction::start_refused, "board not connected"));
        EXPECT_EQ(store.get(id).state, JobState::planned);  // a fresh start: nothing moved
        EXPECT_EQ(store.get(id).reason, "board not connected");
        store.request(id, JobAction::start);
        store.apply(id, JobAction::print_started);
        store.journal(id)->confirmed({.sequence = 3});
        ASSERT_TRUE(store.apply(id, JobAction::faulted, "board unplugged"));
        EXPECT_EQ(store.get(id).state, JobState::paused);  // safe, waits for the operator
        EXPECT_EQ(store.get(id).last_confirmed_event, 3);
    }
    JobStore store(options());
    store.load_all();
    EXPECT_EQ(store.request(1, JobAction::resume).state, JobState::starting);
    ASSERT_TRUE(store.apply(1, JobAction::start_refused, "hotend did not heat"));
    EXPECT_EQ(store.get(1).state, JobState::interrupted);  // a resume stays resumable
}

TEST_F(JobStoreTest, StateWriteIsAtomicAndLeftoverTempFilesAreIgnored) {
    {
        JobStore store(options());
        store.load_all();
        drive(store, store.submit(input_).id, JobState::planned);
    }
    // A write cut short by a crash leaves only its temporary file; state.json is the old one.
    const fs::path temp = state_file(1).string() + ".tmp-4242-0";
    std::ofstream(temp) << "{\"format\": \"fibrecell.job/1\", \"id\": 1, \"sta";
    EXPECT_TRUE(is_leftover_temp_file(temp));
    EXPECT_FALSE(is_leftover_temp_file(state_file(1)));
    JobStore store(options());
    const LoadReport report = store.load_all();
    EXPECT_EQ(report.loaded, std::vector<std::int64_t>{1});
    EXPECT_TRUE(report.failed.empty());
    EXPECT_EQ(store.get(1).state, JobState::planned);
    EXPECT_FALSE(fs::exists(temp));
}

TEST_F(JobStoreTest, JournalAppendsAndReadsBack) {
    const fs::path path = dir_ / "journal.jsonl";
    {
        JobJournal j(path);
        j.sending({.sequence = 1, .kind = drivers::abb::EventKind::head_switch, .layer = 0});
        j.confirmed({.sequence = 1, .kind = drivers::abb::EventKind::head_switch, .layer = 0});
        j.sending(
            {.sequence = 2, .kind = drivers::abb::EventKind::extrude_on, .layer = 0, .path = 0});
        EXPECT_EQ(j.last_sent(), 2);
        EXPECT_EQ(j.last_confirmed(), 1);
    }
    std::istringstream lines(read_file(path));
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line, R"({"kind":"head_switch","layer":0,"path":-1,"phase":"sending","seq":1})");
    const JournalSummary s = read_journal(path);
    EXPECT_EQ(s.records, 3u);
    EXPECT_EQ(s.last_sent, 2);
    EXPECT_EQ(s.last_confirmed, 1);
    EXPECT_FALSE(s.torn_tail);
    // Appending goes on after the reopen; a resumed run's re-confirmations never lower it.
    JobJournal j(path, s);
    j.resumed(2);
    j.confirmed({.sequence = 2});
    j.confirmed({.sequence = 1});
    j.flush();  // confirmed records are queued for the journal's writer
    EXPECT_EQ(read_journal(path).last_confirmed, 2);
    EXPECT_EQ(read_journal(path).records, 6u);
}

TEST_F(JobStoreTest, TheJournalKeepsTheLastFibreFedAndRefusesABadOne) {
    const fs::path path = dir_ / "journal.jsonl";
    {
        JobJournal j(path);
        EXPECT_FALSE(j.last_fed());
        j.fed({8, 12.5});
        j.confirmed({.sequence = 8, .kind = drivers::abb::EventKind::fibre_start});
        j.fed({8, 31.25});
        EXPECT_EQ(j.last_fed()->mm, 31.25);
    }
    EXPECT_THAT(read_file(path), HasSubstr(R"({"mm":31.25,"phase":"fed","seq":8})"));
    const JournalSummary s = read_journal(path);
    ASSERT_TRUE(s.fed);
    EXPECT_EQ(s.fed->sequence, 8);
    EXPECT_EQ(s.fed->mm, 31.25);
    EXPECT_EQ(s.last_confirmed, 8);
    EXPECT_EQ(JobJournal(path, s).last_fed()->mm, 31.25);

    std::ofstream(path) << "{\"seq\":8,\"phase\":\"fed\",\"mm\":-1}\n{\"seq\":9,\"phase\":\"confirmed\"}\n";
    try {
        read_journal(path);
        FAIL();
    } catch (const JournalError& e) {
        EXPECT_EQ(std::string(e.what()),
                  path.string() + ": line 1: a fed record needs a positive integer seq and mm >= 0");
    }
}

TEST_F(JobStoreTest, TornJournalTailIsCutAndBadLinesAreNamed) {
    const fs::path path = dir_ / "journal.jsonl";
    std::ofstream(path) << R"({"seq":1,"phase":"confirmed"})"
                        << "\n"
                        << R"({"seq":2,"phase":"confir)";
    const JournalSummary s = read_journal(path);
    EXPECT_TRUE(s.torn_tail);
    EXPECT_EQ(s.last_confirmed, 1);
    repair_journal(path);
    JobJournal(path, s).confirmed({.sequence = 2});
    EXPECT_EQ(read_journal(path).last_confirmed, 2);
    EXPECT_FALSE(read_journal(path).torn_tail);

    std::ofstream(path) << "{\"seq\":1,\"phase\":\"confirmed\"}\nnot json\n{\"seq\":2,\"phase\":"
                           "\"confirmed\"}\n";
    try {
        read_journal(path);
        FAIL();
    } catch (const JournalError& e) {
        EXPECT_EQ(std::string(e.what()), path.string() + ": line 2: not a journal record");
    }
}

TEST_F(JobStoreTest, CrashWhilePrintingComesBackInterruptedWithTheLastEvent) {
    {
        JobStore store(options());
        const auto id = printing_job(store);
        auto journal = store.journal(id);
        for (std::int64_t seq = 1; seq <= 5; ++seq) {
            journal->sending({.sequence = seq});
            journal->confirmed({.sequence = seq});
        }
        journal->sending({.sequence = 6});
        // No clean shutdown: the store is dropped as a crash would leave the disk.
    }
    JobStore store(options());
    const LoadReport report = store.load_all();
    EXPECT_EQ(report.interrupted, std::vector<std::int64_t>{1});
    const JobRecord r = store.get(1);
    EXPECT_EQ(r.state, JobState::interrupted);
    EXPECT_EQ(r.last_confirmed_event, 5);
    EXPECT_EQ(r.reason, "the service restarted while the job was printing; last confirmed event 5");
    EXPECT_EQ(store.journal(1)->last_sent(), 6);
    const auto disk = nlohmann::json::parse(read_file(state_file(1)));
    EXPECT_EQ(disk["state"], "interrupted");
    EXPECT_EQ(disk["last_confirmed_event"], 5);
    // It may be resumed (back through starting) or aborted.
    EXPECT_EQ(store.request(1, JobAction::resume).state, JobState::starting);
}

TEST_F(JobStoreTest, StateJsonFollowsThePrintsProgress) {
    JobStore store(options());
    const auto id = printing_job(store);
    store.confirm_progress(id, 7);
    EXPECT_EQ(nlohmann::json::parse(read_file(state_file(id)))["last_confirmed_event"], 7);
    store.confirm_progress(id, 3);  // never backwards
    EXPECT_EQ(nlohmann::json::parse(read_file(state_file(id)))["last_confirmed_event"], 7);
}

TEST_F(JobStoreTest, AFaultsReasonStaysWhileItHoldsTheJobAndGoesWhenThePrintGoesOn) {
    JobStore store(options());
    const auto id = printing_job(store);
    store.apply(id, JobAction::faulted, "robot heartbeat lost for 5026 ms");
    EXPECT_EQ(store.get(id).reason, "robot heartbeat lost for 5026 ms");
    store.request(id, JobAction::resume);
    EXPECT_EQ(store.get(id).reason, "");  // starting again: the fault is over
    store.apply(id, JobAction::print_done, "");
    EXPECT_EQ(store.get(id).state, JobState::completed);
    EXPECT_EQ(nlohmann::json::parse(read_file(state_file(id)))["reason"], "");
    // A paused job that then fails without a word of its own keeps the fault that paused it.
    const auto other = store.submit(input_).id;
    drive(store, other, JobState::printing);
    store.apply(other, JobAction::faulted, "the extruder board is not connected");
    store.apply(other, JobAction::print_failed, "");
    EXPECT_EQ(store.get(other).reason, "the extruder board is not connected");
}

TEST_F(JobStoreTest, AJobWhoseJournalIsLostResumesOnlyOnTheOperatorsWord) {
    {
        JobStore store(options());
        const auto id = printing_job(store);
        auto journal = store.journal(id);
        for (std::int64_t seq = 1; seq <= 9; ++seq) journal->confirmed({.sequence = seq});
        store.confirm_progress(id, 7);  // the last layer began at event 7
    }
    fs::remove(dir_ / "state" / "jobs" / "1" / "journal.jsonl");
    for (int restart = 0; restart < 2; ++restart) {  // the refusal survives a second restart
        JobStore store(options());
        const LoadReport report = store.load_all();
        EXPECT_THAT(report.warnings, ::testing::Contains(::testing::HasSubstr(
                                         "job 1; its journal.jsonl is missing")));
        const JobRecord r = store.get(1);
        EXPECT_EQ(r.state, JobState::interrupted);
        EXPECT_EQ(r.last_confirmed_event, 7);
        EXPECT_THAT(r.reason, ::testing::HasSubstr("resume needs the operator's word"));
        try {
            store.request(1, JobAction::resume);
            FAIL() << "a job whose journal is lost resumed";
        } catch (const JobConflict& e) {
            EXPECT_THAT(e.what(), ::testing::HasSubstr("known only up to event 7"));
            EXPECT_THAT(e.what(), ::testing::HasSubstr("--journal-lost"));
        }
        EXPECT_TRUE(nlohmann::json::parse(read_file(state_file(1)))["journal_lost"]);
    }
    JobStore store(options());
    store.load_all();
    store.accept_lost_journal(1);
    EXPECT_EQ(store.request(1, JobAction::resume).state, JobState::starting);
    EXPECT_FALSE(nlohmann::json::parse(read_file(state_file(1)))["journal_lost"]);
}

TEST_F(JobStoreTest, EveryCellHoldingStateComesBackInterrupted) {
    for (JobState s : {JobState::starting, JobState::pausing, JobState::paused}) {
        fs::remove_all(dir_ / "state");
        {
            JobStore store(options());
            store.load_all();
            drive(store, store.submit(input_).id, s);
        }
        JobStore store(options());
        EXPECT_EQ(store.load_all().interrupted, std::vector<std::int64_t>{1}) << to_string(s);
        EXPECT_EQ(store.get(1).state, JobState::interrupted) << to_string(s);
    }
    // Ended and planned jobs stay as they were.
    fs::remove_all(dir_ / "state");
    {
        JobStore store(options());
        store.load_all();
        drive(store, store.submit(input_).id, JobState::planned);
        drive(store, store.submit(input_).id, JobState::completed);
    }
    JobStore store(options());
    EXPECT_TRUE(store.load_all().interrupted.empty());
    EXPECT_EQ(store.get(1).state, JobState::planned);
    EXPECT_EQ(store.get(2).state, JobState::completed);
}

TEST_F(JobStoreTest, PlanningIsRetriedAfterRestartsUpToTheLimit) {
    {
        JobStore store(options());
        store.load_all();
        store.submit(input_);  // queued, never begun
        store.submit(input_);
        store.submit(input_);
        ASSERT_TRUE(store.begin_planning(2));                 // one attempt cut short
        for (int i = 0; i < 4; ++i) store.begin_planning(3);  // the 4th attempt cut short
    }
    JobStore store(options());
    const LoadReport report = store.load_all();
    EXPECT_EQ(report.to_plan, (std::vector<std::int64_t>{1, 2}));
    EXPECT_EQ(report.failed, std::vector<std::int64_t>{3});
    EXPECT_EQ(store.get(2).plan_attempts, 1);
    EXPECT_EQ(store.get(3).state, JobState::failed);
    EXPECT_EQ(store.get(3).reason,
              "planning was cut short by 4 restarts of the service; not retried again");
    // A worker stopped by a clean shutdown does not count.
    store.begin_planning(1);
    store.planning_stopped(1);
    EXPECT_EQ(store.get(1).plan_attempts, 0);
    EXPECT_EQ(store.begin_planning(3), std::nullopt);  // not planning any more
}

TEST_F(JobStoreTest, CorruptStateOfOneJobIsIsolated) {
    {
        JobStore store(options());
        store.load_all();
        for (int i = 0; i < 5; ++i) drive(store, store.submit(input_).id, JobState::planned);
    }
    std::ofstream(state_file(2), std::ios::trunc) << "{\"format\": \"fibrecell.job/1\", \"id\": ";
    auto j = nlohmann::json::parse(read_file(state_file(3)));
    j.erase("state");
    std::ofstream(state_file(3), std::ios::trunc) << j.dump();
    j = nlohmann::json::parse(read_file(state_file(4)));
    j["state"] = "dancing";
    std::ofstream(state_file(4), std::ios::trunc) << j.dump();

    const fs::path journal = state_file(5).parent_path() / "journal.jsonl";
    std::ofstream(journal)
        << "{\"seq\":1,\"phase\":\"confirmed\"}\n{\"seq\":2,\"phase\":\"eaten\"}\n"
           "{\"seq\":3,\"phase\":\"confirmed\"}\n";

    JobStore store(options());
    const LoadReport report = store.load_all();
    EXPECT_EQ(report.loaded, (std::vector<std::int64_t>{1, 2, 3, 4, 5}));
    EXPECT_EQ(report.failed, (std::vector<std::int64_t>{2, 3, 4, 5}));
    EXPECT_EQ(store.get(1).state, JobState::planned);
    EXPECT_EQ(store.get(2).state, JobState::failed);
    EXPECT_EQ(store.get(2).reason, state_file(2).string() + ": not valid JSON");
    EXPECT_EQ(store.get(3).reason, state_file(3).string() + ": state: missing");
    EXPECT_EQ(store.get(4).reason, state_file(4).string() + ": state: unknown job state 'dancing'");
    EXPECT_EQ(store.get(5).reason, journal.string() + ": line 2: unknown phase 'eaten'");
    // The broken job can be removed; the good one still starts.
    store.request(2, JobAction::remove);
    EXPECT_EQ(store.request(1, JobAction::start).state, JobState::starting);
}

TEST_F(JobStoreTest, IdsGrowAcrossRestartsAndRemovals) {
    {
        JobStore store(options());
        store.load_all();
        store.submit(input_);
        store.submit(input_);
        store.request(2, JobAction::abort);
        store.request(2, JobAction::remove);
    }
    {
        JobStore store(options());
        store.load_all();
        EXPECT_EQ(store.next_id(), 3);  // 2 was removed, never given again
        EXPECT_EQ(store.submit(input_).id, 3);
    }
    // Without next_id (lost), ids continue after the highest job folder.
    fs::remove(dir_ / "state" / "next_id");
    JobStore store(options());
    store.load_all();
    EXPECT_EQ(store.submit(input_).id, 4);
}

TEST_F(JobStoreTest, OnlyTheNewestEndedJobsAreKept) {
    JobStoreOptions o = options();
    o.keep_completed = 2;
    JobStore store(o);
    store.load_all();
    for (int i = 0; i < 4; ++i) store.submit(input_);
    for (std::int64_t id = 1; id <= 4; ++id) store.request(id, JobAction::abort);
    std::vector<std::int64_t> ids;
    for (const auto& r : store.list()) ids.push_back(r.id);
    EXPECT_EQ(ids, (std::vector<std::int64_t>{3, 4}));
    EXPECT_FALSE(fs::exists(state_file(1).parent_path()));
}
