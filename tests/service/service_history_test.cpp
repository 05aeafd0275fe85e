// The cell's history (docs/history.md) against the real service over its socket, with the mock
// GT2560 as a process of its own that logs every command it runs: after a completed, an aborted
// and an interrupted print (the service stopped mid-print and started again) there is one record
// each, and the filament each says it used is what the board's own log shows it ran, to 0.1 mm.
// The CSV export is read back with an RFC 4180 reader of the test's own: a header, one row a
// job, a name that a spreadsheet would run as a formula written as text.
#include "external_cell.hpp"
#include "service_fixture.hpp"

#include <gmock/gmock.h>

#include <array>
#include <sstream>
#include <string>
#include <vector>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

namespace {

// RFC 4180: fields separated by commas, records by CRLF, a quoted field may hold commas, CRLF
// and doubled quotes.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
    std::vector<std::vector<std::string>> rows(1);
    std::string field;
    bool quoted = false, was_quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                field += c;
            }
        } else if (c == '"' && field.empty() && !was_quoted) {
            quoted = was_quoted = true;
        } else if (c == ',') {
            rows.back().push_back(field);
            field.clear();
            was_quoted = false;
        } else if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') {
            rows.back().push_back(field);
            field.clear();
            was_quoted = false;
            rows.emplace_back();
            ++i;
        } else {
            field += c;  // a bare quote or line break would be malformed: kept, and the test fails
        }
    }
    if (rows.back().empty()) rows.pop_back();  // after the last CRLF
    return rows;
}

// The fibre the journal says the job took so far [mm] (its last `used` record).
double journal_fibre_mm(const fs::path& journal) {
    std::ifstream in(journal);
    std::string line;
    double mm = 0;
    while (std::getline(in, line))
        if (line.find("\"used\"") != std::string::npos && line.back() == '}')
            mm = json::parse(line).value("fibre_mm", 0.0);
    return mm;
}

}  // namespace

TEST_F(ServiceTest, TheHistoryRecordsWhatTheBoardFedForACompletedAnAbortedAndAnInterruptedPrint) {
    ExternalCell devices(dir_, 40);
    ASSERT_TRUE(devices.up());
    std::ofstream(dir_ / "cell.yaml") << devices.cell_yaml(read_file(write_config("", 40)));
    // A name a spreadsheet would run as a formula, with a comma and quotes besides.
    const std::string formula = "=cmd|' /C calc'!A0, \"x\"";
    std::ofstream(dir_ / "jobs/formula.job.yaml")
        << "name: \"=cmd|' /C calc'!A0, \\\"x\\\"\"\nmodel:\n  mesh: bar.vtk\n"
           "placement:\n  position_mm: [150, 150]\nprocess:\n  pla: {speed_mm_s: 24}\n  ccf: {speed_mm_s: 10}\n";
    start_service(dir_ / "cell.yaml");
    const auto board = [&] { return devices.board_fed(); };
    const auto job_journal = [&](std::int64_t id) {
        return state_dir() / "jobs" / std::to_string(id) / "journal.jsonl";
    };
    // The board's totals once they reach `fibre_mm` (its log is written as it runs).
    const auto board_reaches = [&](double fibre_mm) {
        eventually([&] { return std::abs(board()[1] - fibre_mm) < 0.05; }, 10s, 20ms);
        return board();
    };

    auto c = client();
    // 1. Completed.
    const std::int64_t completed = submit_bar(c, true);
    ASSERT_TRUE(printed(wait_for_state(c, completed, "completed", 120s))) << service_->log();
    json first;  // recorded as the job's end is published: soon after, not with it
    ASSERT_TRUE(eventually([&] {
        first = c.call("history.list");
        return first.value("count", 0) == 1;
    }, 10s)) << first.dump(2);
    const std::array<double, 2> after_completed =
        board_reaches(first["records"][0].value("fibre_used_m", 0.0) * 1000);
    c.call("cell.clear");

    // 2. Aborted, with fibre laid.
    const std::int64_t aborted =
        c.call("job.submit", submit_params(dir_ / "jobs/formula.job.yaml", "bar.vtk", true), 30s)
            .value("id", std::int64_t{0});
    ASSERT_TRUE(eventually([&] { return journal_fibre_mm(job_journal(aborted)) > 60; }, 120s, 5ms))
        << service_->log();
    c.call("job.abort", {{"job", aborted}});
    ASSERT_EQ(wait_for_state(c, aborted, "aborted").value("state", ""), "aborted");
    ASSERT_TRUE(eventually([&] { return c.call("cell.status")["job"].is_null(); }, 30s));
    json records;
    ASSERT_TRUE(eventually([&] {
        records = c.call("history.list")["records"];
        return records.size() == 2;
    }, 10s));
    const std::array<double, 2> after_aborted = board_reaches(
        after_completed[1] + records[1].value("fibre_used_m", 0.0) * 1000);
    c.call("cell.clear");

    // 3. Interrupted: the service is stopped mid-print and started again.
    const std::int64_t interrupted = submit_bar(c, true);
    ASSERT_TRUE(eventually([&] { return journal_fibre_mm(job_journal(interrupted)) > 60; }, 120s, 5ms))
        << service_->log();
    ASSERT_TRUE(service_->terminate(30s)) << service_->log();
    start_service(dir_ / "cell.yaml");
    c = client();
    ASSERT_EQ(c.call("job.get", {{"job", interrupted}}).value("state", ""), "interrupted");

    const json all = c.call("history.list");
    ASSERT_EQ(all.value("count", 0), 3) << all.dump(2);
    const json& r = all["records"];
    std::vector<std::string> outcomes;
    for (const json& x : r) outcomes.push_back(x.value("outcome", ""));
    EXPECT_THAT(outcomes, ElementsAre(::testing::AnyOf("completed", "completed_with_warnings"),
                                      "aborted", "interrupted"));
    const std::array<double, 2> after_interrupted =
        board_reaches(after_aborted[1] + r[2].value("fibre_used_m", 0.0) * 1000);

    // Each record's filament is the board's, job by job, to 0.1 mm.
    const std::array<std::array<double, 2>, 3> ran = {
        after_completed,
        {after_aborted[0] - after_completed[0], after_aborted[1] - after_completed[1]},
        {after_interrupted[0] - after_aborted[0], after_interrupted[1] - after_aborted[1]}};
    for (std::size_t i = 0; i < 3; ++i) {
        std::printf("job %lld %s: fibre %.2f mm used (board %.2f), planned %.2f mm; PLA %.2f mm used "
                    "(board %.2f), planned %.2f mm\n",
                    static_cast<long long>(r[i].value("id", 0)), r[i].value("outcome", "").c_str(),
                    r[i].value("fibre_used_m", 0.0) * 1000, ran[i][1],
                    r[i].value("fibre_planned_m", 0.0) * 1000, r[i].value("pla_used_m", 0.0) * 1000,
                    ran[i][0], r[i].value("pla_planned_m", 0.0) * 1000);
        EXPECT_NEAR(r[i].value("fibre_used_m", 0.0) * 1000, ran[i][1], 0.1) << r[i].dump(2);
        EXPECT_NEAR(r[i].value("pla_used_m", 0.0) * 1000, ran[i][0], 0.1) << r[i].dump(2);
        EXPECT_GT(ran[i][1], 60);
    }
    // The completed print used what it planned (fibre: path for path, the thread included).
    EXPECT_NEAR(r[0].value("fibre_used_m", 0.0), r[0].value("fibre_planned_m", 0.0), 0.005);
    EXPECT_EQ(r[0].value("layers_printed", 0), r[0].value("layers_total", -1));
    EXPECT_GT(r[0].value("layers_total", 0), 0);
    EXPECT_TRUE(r[0]["cut_error_p99_mm"].is_number()) << r[0].dump(2);
    EXPECT_LT(r[1].value("layers_printed", 99), r[1].value("layers_total", 0));
    EXPECT_EQ(r[1].value("name", ""), formula);
    EXPECT_THAT(r[1].value("reason", ""), HasSubstr("aborted"));
    EXPECT_THAT(r[2].value("reason", ""), HasSubstr("restarted"));
    for (const json& x : r) {
        EXPECT_EQ(x.value("strategy", ""), "field");
        EXPECT_EQ(x.value("submitted_by", ""), x.value("started_by", "?"));  // submitted with start
        EXPECT_FALSE(x.value("submitted_by", "").empty());
        for (const char* t : {"submitted_at", "planned_at", "started_at", "ended_at"})
            EXPECT_FALSE(x.value(t, "").empty()) << t;
    }

    // The CSV, read back.
    const std::string csv = c.call("history.list", {{"format", "csv"}}).value("csv", "");
    const auto rows = parse_csv(csv);
    ASSERT_EQ(rows.size(), 4u) << csv;
    const std::vector<std::string>& header = rows[0];
    const auto column = [&](const std::string& name) {
        const auto at = std::find(header.begin(), header.end(), name);
        EXPECT_NE(at, header.end()) << name;
        return static_cast<std::size_t>(at - header.begin());
    };
    for (std::size_t i = 1; i < rows.size(); ++i) {
        ASSERT_EQ(rows[i].size(), header.size()) << csv;
        const json& x = r[i - 1];
        EXPECT_EQ(rows[i][column("id")], std::to_string(x.value("id", 0)));
        EXPECT_NEAR(std::stod(rows[i][column("fibre_used_m")]), x.value("fibre_used_m", 0.0), 1e-5);
        EXPECT_NEAR(std::stod(rows[i][column("pla_used_m")]), x.value("pla_used_m", 0.0), 1e-5);
        EXPECT_EQ(rows[i][column("outcome")], x.value("outcome", ""));
    }
    // The formula is text: one apostrophe before it, dropped by a reader, gives the name back.
    EXPECT_EQ(rows[2][column("name")], "'" + formula);
    EXPECT_EQ(rows[2][column("name")].substr(1), formula);
    EXPECT_EQ(rows[1][column("name")], "bar");

    // --since and bad input.
    EXPECT_EQ(c.call("history.list", {{"since", "2999-01-01"}}).value("count", -1), 0);
    EXPECT_EQ(c.call("history.list", {{"limit", 1}})["records"][0].value("id", 0), interrupted);
    for (const json& bad : {json{{"since", "yesterday"}}, json{{"format", "xlsx"}},
                            json{{"limit", -1}}, json{{"colour", "red"}}}) {
        try {
            c.call("history.list", bad);
            ADD_FAILURE() << bad.dump() << " was accepted";
        } catch (const api::ApiCallError& e) {
            EXPECT_EQ(e.code(), -32602) << e.what();
            EXPECT_THAT(e.what(), HasSubstr("history.list")) << e.what();
        }
    }
}

// Retention (docs/history.md, "Keeping it"): a record older than keep_days and those beyond keep
// are dropped as records come; with prune_plans the plan of a dropped record's job goes too, but
// only of a job that ended: an interrupted job keeps its plan for its resume. A line of the file
// that cannot be read is skipped and named; the rest loads.
TEST_F(ServiceTest, TheHistoryKeepsWhatItIsToldAndPrunesOnlyThePlansOfEndedJobs) {
    fs::create_directories(state_dir());
    std::ofstream(state_dir() / "history.jsonl")
        << R"({"id":90,"name":"old","outcome":"completed","ended_at":"2000-01-01T00:00:00Z"})" "\n"
        << "not a record\n";
    const fs::path config = write_config("history: {keep: 1, keep_days: 30, prune_plans: true}\n");
    start_service(config);
    auto c = client();
    EXPECT_EQ(c.call("history.list").value("count", 0), 1);
    EXPECT_THAT(service_->log(), HasSubstr("history.record_unreadable history.jsonl line 2"));
    const auto ids = [&] {
        std::vector<std::int64_t> out;
        const json list = c.call("history.list");
        for (const json& r : list["records"]) out.push_back(r.value("id", std::int64_t{0}));
        return out;
    };
    const auto plan_of = [&](std::int64_t id) { return state_dir() / "jobs" / std::to_string(id) / "plan" / "report.json"; };

    // An aborted job: the 26-year-old record goes (by age and by count).
    const std::int64_t aborted = submit_bar(c, false);
    ASSERT_EQ(wait_for_state(c, aborted, "planned", 120s).value("state", ""), "planned");
    c.call("job.abort", {{"job", aborted}});
    ASSERT_TRUE(eventually([&] { return ids() == std::vector<std::int64_t>{aborted}; }, 10s)) << c.call("history.list").dump(2);
    EXPECT_TRUE(fs::exists(plan_of(aborted)));

    // An interrupted print: the aborted job's record goes, and its plan with it.
    c.call("cell.clear");
    const std::int64_t interrupted = submit_bar(c, true);
    ASSERT_EQ(wait_for_state(c, interrupted, "printing", 120s).value("state", ""), "printing");
    ASSERT_TRUE(service_->terminate(30s));
    start_service(config);
    c = client();
    ASSERT_EQ(c.call("job.get", {{"job", interrupted}}).value("state", ""), "interrupted");
    EXPECT_EQ(ids(), std::vector<std::int64_t>{interrupted});
    EXPECT_FALSE(fs::exists(plan_of(aborted)));

    // A failed plan: the interrupted job's record goes; its plan stays for its resume.
    const std::int64_t failed = submit_broken(c);
    ASSERT_EQ(wait_for_state(c, failed, "failed").value("state", ""), "failed");
    ASSERT_TRUE(eventually([&] { return ids() == std::vector<std::int64_t>{failed}; }, 10s)) << c.call("history.list").dump(2);
    EXPECT_TRUE(fs::exists(plan_of(interrupted)));
    const json record = c.call("history.list")["records"][0];
    EXPECT_EQ(record.value("outcome", ""), "failed");
    EXPECT_TRUE(record["fibre_used_m"].is_null()) << record.dump(2);  // it never printed
    EXPECT_EQ(record.value("started_at", "?"), "");

    // A restart brings back none of the dropped records (their jobs are still in the store),
    // nor records the kept one again.
    ASSERT_TRUE(service_->terminate(30s));
    start_service(config);
    c = client();
    EXPECT_EQ(ids(), std::vector<std::int64_t>{failed});
    EXPECT_EQ(service_->log().find("history.recorded"), std::string::npos) << service_->log();
}
