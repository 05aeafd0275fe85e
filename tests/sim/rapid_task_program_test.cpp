// The simulated RAPID task running small programs on its thread in simulated time: arithmetic and
// control flow, routines with arguments, records and arrays, run-time errors naming module and
// line, WaitUntil \MaxTime, interrupts (ISignalDI, ITimer, ISleep), data access while running,
// and start/stop/reset/destructor in every order (none may block).
#include "drivers/sim/rapid_exec/rapid_task.hpp"

#include "drivers/abb/rapid/reader.hpp"
#include "tests/support/eventually.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_rapid_task_program_test {

using namespace fibrecell::drivers;
using namespace fibrecell::drivers::sim;
using namespace std::chrono_literals;
using fibrecell::test::eventually;

namespace {

// The controller's I/O as a map; every write and log line recorded.
class Io {
  public:
    Io() {
        values_ = {{"diGo", 0}, {"diStep", 0}, {"giCode", 0}, {"doLamp", 0}, {"goCode", 0}};
    }
    TaskIo task_io() {
        return {.read_signal =
                    [this](const std::string& s) {
                        const std::lock_guard g(mu_);
                        return values_.at(s);
                    },
                .write_signal =
                    [this](const std::string& s, double v) {
                        const std::lock_guard g(mu_);
                        values_.at(s) = v;
                        writes_.emplace_back(s, v);
                    },
                .read_file = [](const std::string&) { return std::optional<std::string>(); },
                .log =
                    [this](const std::string& text) {
                        const std::lock_guard g(mu_);
                        log_.push_back(text);
                    },
                .known_signals = {"diGo", "diStep", "giCode", "doLamp", "goCode"}};
    }
    // An input changes: the map, then the task (as the I/O side does).
    void set_input(RapidTask& task, const std::string& s, double v) {
        {
            const std::lock_guard g(mu_);
            values_.at(s) = v;
        }
        task.signal_changed(s, v);
    }
    double value(const std::string& s) {
        const std::lock_guard g(mu_);
        return values_.at(s);
    }
    std::vector<std::string> log() {
        const std::lock_guard g(mu_);
        return log_;
    }

  private:
    std::mutex mu_;
    std::map<std::string, double> values_;
    std::vector<std::pair<std::string, double>> writes_;
    std::vector<std::string> log_;
};

abb::rapid::Module module_of(const std::string& text) {
    abb::rapid::ValidateOptions o;
    o.known_signals = {"diGo", "diStep", "giCode", "doLamp", "goCode"};
    return abb::rapid::read_module(text, o);
}

class RapidTaskProgram : public ::testing::Test {
  protected:
    SimClock clock{20};
    MotionSimulator motion{clock};
    Io io;
    RapidTask task{clock, motion, io.task_io()};

    // Loads `text`, starts it and waits until the task is no longer running.
    TaskStatus run(const std::string& text) {
        task.load(module_of(text));
        task.reset_pp();
        task.start();
        EXPECT_TRUE(finished());
        return task.status();
    }
    bool finished() {
        return eventually([&] { return task.status().state != TaskState::running; });
    }
    double num(const std::string& name) { return task.read_data("T", name).num(); }
    bool boolean(const std::string& name) { return task.read_data("T", name).boolean(); }
};

}  // namespace

TEST_F(RapidTaskProgram, ArithmeticAndControlFlow) {
    const TaskStatus s = run(R"(MODULE T
  PERS num nOut := 0;
  PERS string sOut := "";
  PROC main()
    VAR num n := 0;
    FOR i FROM 1 TO 10 DO
      n := n + i;
    ENDFOR
    WHILE n < 100 DO
      n := n * 2;
    ENDWHILE
    TEST n MOD 7
    CASE 1, 2:
      sOut := "small";
    CASE 5:
      sOut := "five";
    DEFAULT:
      sOut := "other";
    ENDTEST
    IF n > 1000 THEN
      nOut := -1;
    ELSEIF n > 100 THEN
      nOut := n DIV 3 + Abs(-0.5);
    ELSE
      nOut := -2;
    ENDIF
    FOR k FROM 10 TO 1 STEP -3 DO
      sOut := sOut + NumToStr(k, 0);
    ENDFOR
  ENDPROC
ENDMODULE
)");
    EXPECT_EQ(s.state, TaskState::stopped) << s.error;
    EXPECT_EQ(num("nOut"), 36.5);  // 55 -> 110; 110 DIV 3 + 0.5
    EXPECT_EQ(task.read_data("T", "sOut").string(), "five10741");  // 110 MOD 7 = 5
}

TEST_F(RapidTaskProgram, RoutinesWithArguments) {
    const TaskStatus s = run(R"(MODULE T
  PERS num nFact := 0;
  PERS num nSum := 0;
  PERS num nIn := 5;
  PERS num nOpt := 0;
  PROC main()
    VAR num n := 3;
    nFact := Fact(5);
    AddTo nSum, n;
    AddTo nSum, 4;
    KeepIn nIn;
    nOpt := Opt(2) * 10 + Opt(2 \Extra:=7);
  ENDPROC
  FUNC num Fact(num k)
    IF k <= 1 THEN
      RETURN 1;
    ENDIF
    RETURN k * Fact(k - 1);
  ENDFUNC
  PROC AddTo(INOUT num total, num amount)
    total := total + amount;
  ENDPROC
  PROC KeepIn(num copy)
    copy := copy + 100;
  ENDPROC
  FUNC num Opt(num a, \num Extra)
    IF Present(Extra) THEN
      RETURN a + Extra;
    ENDIF
    RETURN a;
  ENDFUNC
ENDMODULE
)");
    EXPECT_EQ(s.state, TaskState::stopped) << s.error;
    EXPECT_EQ(num("nFact"), 120);
    EXPECT_EQ(num("nSum"), 7);
    EXPECT_EQ(num("nIn"), 5);  // an IN parameter is a copy
    EXPECT_EQ(num("nOpt"), 29);
}

TEST_F(RapidTaskProgram, RecordsAndArrays) {
    const TaskStatus s = run(R"(MODULE T
  PERS robtarget pOut := [[0,0,0],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PERS num nGrid{2,3} := [[0,0,0],[0,0,0]];
  PERS pos xSum := [0,0,0];
  PROC main()
    VAR num nList{3} := [1, 2, 3];
    VAR pos a := [1, 2, 3];
    pOut.trans.x := 5;
    pOut.trans := pOut.trans + [0, 10, 0];
    pOut.robconf.cfx := 1;
    FOR r FROM 1 TO 2 DO
      FOR c FROM 1 TO 3 DO
        nGrid{r, c} := r * 10 + nList{c};
      ENDFOR
    ENDFOR
    nList{2} := nList{1} + nList{3};
    xSum := a * 2 + [nList{2}, 0, 0];
  ENDPROC
ENDMODULE
)");
    EXPECT_EQ(s.state, TaskState::stopped) << s.error;
    const auto p = abb::rapid::to_robtarget(task.read_data("T", "pOut"));
    ASSERT_TRUE(p);
    EXPECT_EQ(p->trans_mm, Eigen::Vector3d(5, 10, 0));
    EXPECT_EQ(p->conf.cfx, 1);
    const abb::rapid::Value grid = task.read_data("T", "nGrid");
    EXPECT_EQ(grid.items()[1].items()[2].num(), 23);
    EXPECT_EQ(grid.items()[0].items()[0].num(), 11);
    const abb::rapid::Value x = task.read_data("T", "xSum");
    EXPECT_EQ(x.items()[0].num(), 6);  // 2 + nList{2} = 2 + 4
    EXPECT_EQ(x.items()[2].num(), 6);
}

TEST_F(RapidTaskProgram, RunTimeErrorNamesModuleAndLine) {
    const TaskStatus s = run(R"(MODULE T
  PERS num nOut := 0;
  PROC main()
    VAR num n := 0;
    nOut := 1;
    Divide n;
    nOut := 2;
  ENDPROC
  PROC Divide(num d)
    nOut := 10 / d;
  ENDPROC
ENDMODULE
)");
    EXPECT_EQ(s.state, TaskState::error);
    EXPECT_EQ(s.error, "T line 10: division by zero");
    EXPECT_EQ(num("nOut"), 1);  // stopped at the error
    ASSERT_FALSE(io.log().empty());
    EXPECT_NE(io.log().back().find("T line 10"), std::string::npos);
}

TEST_F(RapidTaskProgram, IndexOutsideTheArrayIsAnError) {
    const TaskStatus s = run(R"(MODULE T
  VAR num nList{3} := [1, 2, 3];
  PROC main()
    VAR num i := 4;
    nList{i} := 0;
  ENDPROC
ENDMODULE
)");
    EXPECT_EQ(s.state, TaskState::error);
    EXPECT_EQ(s.error, "T line 5: index 4 of 'nList' outside 1..3");
}

TEST_F(RapidTaskProgram, InstructionOutsideTheExecutedSubsetIsAnError) {
    const TaskStatus s = run(R"(MODULE T
  PROC main()
    SetDO doLamp, 1;
    PulseDO doLamp;
  ENDPROC
ENDMODULE
)");
    EXPECT_EQ(s.state, TaskState::error);
    EXPECT_EQ(s.error, "T line 4: instruction PulseDO is not executed by the simulated controller");
    EXPECT_EQ(io.value("doLamp"), 1);

    // A module the controller was given without the reader's checks: an unknown procedure.
    auto parsed = abb::rapid::parse_module("MODULE U\n  PROC main()\n    Frobnicate 1;\n  ENDPROC\nENDMODULE\n");
    ASSERT_TRUE(parsed.module);
    task.unload("T");
    task.load(*parsed.module);
    task.reset_pp();
    task.start();
    ASSERT_TRUE(finished());
    EXPECT_EQ(task.status().error, "U line 3: unknown procedure 'Frobnicate'");
}

TEST_F(RapidTaskProgram, WaitUntilMaxTimeSetsTheTimeFlagOrFails) {
    const TaskStatus s = run(R"(MODULE T
  PERS bool bLate := FALSE;
  PERS num nWaited := 0;
  PERS bool bGo := FALSE;
  PROC main()
    WaitUntil bGo \MaxTime:=0.5 \TimeFlag:=bLate;
    WaitUntil bGo \MaxTime:=0.2;
    bLate := FALSE;
  ENDPROC
ENDMODULE
)");
    EXPECT_EQ(s.state, TaskState::error);
    EXPECT_EQ(s.error, "T line 7: WaitUntil: \\MaxTime expired (ERR_WAIT_MAXTIME)");
    EXPECT_TRUE(boolean("bLate"));
}

TEST_F(RapidTaskProgram, TrapRunsOnSignalEdgeWhileAnInstructionWaits) {
    // Parsed without the validator: its instruction table has no ISignalGI yet.
    auto parsed = abb::rapid::parse_module(R"(MODULE T
  PERS num nEdges := 0;
  PERS num nCode := 0;
  VAR intnum iGo;
  VAR intnum iCode;
  PROC main()
    CONNECT iGo WITH OnGo;
    ISignalDI diGo, 1, iGo;
    CONNECT iCode WITH OnCode;
    ISignalGI giCode, iCode;
    WaitUntil nEdges >= 2 AND nCode = 7;
    SetDO doLamp, 1;
  ENDPROC
  TRAP OnGo
    Incr nEdges;
  ENDTRAP
  TRAP OnCode
    nCode := GInput(giCode);
  ENDTRAP
ENDMODULE
)");
    ASSERT_TRUE(parsed.module);
    task.load(*parsed.module);
    task.reset_pp();
    task.start();
    ASSERT_TRUE(eventually([&] { return task.status().line == 11; }));
    io.set_input(task, "diGo", 1);  // rising edge: trap
    io.set_input(task, "diGo", 0);  // falling: no trap
    io.set_input(task, "diGo", 1);  // trap
    io.set_input(task, "giCode", 7);
    ASSERT_TRUE(finished());
    EXPECT_EQ(task.status().state, TaskState::stopped) << task.status().error;
    EXPECT_EQ(num("nEdges"), 2);
    EXPECT_EQ(num("nCode"), 7);
    EXPECT_EQ(io.value("doLamp"), 1);
}

TEST_F(RapidTaskProgram, TimerTrapAndSleepingInterrupt) {
    const TaskStatus s = run(R"(MODULE T
  PERS num nTicks := 0;
  PERS num nSlept := 0;
  VAR intnum iTick;
  PROC main()
    CONNECT iTick WITH OnTick;
    ITimer 0.1, iTick;
    WaitTime 1.05;
    ISleep iTick;
    nSlept := nTicks;
    WaitTime 0.5;
    IDelete iTick;
  ENDPROC
  TRAP OnTick
    Incr nTicks;
  ENDTRAP
ENDMODULE
)");
    EXPECT_EQ(s.state, TaskState::stopped) << s.error;
    // 10 expiries in 1.05 s; a late wake-up raises once, never more than one per period.
    EXPECT_GE(num("nSlept"), 8);
    EXPECT_LE(num("nSlept"), 10);
    EXPECT_EQ(num("nTicks"), num("nSlept"));  // asleep: expiries discarded
}

TEST_F(RapidTaskProgram, DataReadAndWrittenWhileRunning) {
    task.load(module_of(R"(MODULE T
  PERS bool bGo := FALSE;
  PERS num nIn := 0;
  PERS num nOut := 0;
  CONST num K := 3;
  PROC main()
    WaitUntil bGo \PollRate:=0.04;
    nOut := nIn * K;
  ENDPROC
ENDMODULE
)"));
    task.reset_pp();
    task.start();
    ASSERT_TRUE(eventually([&] { return task.status().line == 7; }));
    EXPECT_EQ(task.status().module, "T");
    EXPECT_FALSE(boolean("bGo"));
    task.write_data("T", "nIn", abb::rapid::num_value(14));
    EXPECT_THROW(task.write_data("T", "nIn", abb::rapid::string_value("x")),
                 std::invalid_argument);
    EXPECT_THROW(task.write_data("T", "K", abb::rapid::num_value(4)), std::invalid_argument);
    EXPECT_THROW(task.read_data("T", "nNone"), std::out_of_range);
    EXPECT_THROW(task.read_data("X", "nIn"), std::out_of_range);
    task.write_data("T", "bGo", abb::rapid::bool_value(true));
    ASSERT_TRUE(finished());
    EXPECT_EQ(num("nOut"), 42);
}

TEST_F(RapidTaskProgram, StopContinuesWhereItStoppedAndResetStartsOver) {
    task.load(module_of(R"(MODULE T
  PERS num nCount := 0;
  VAR num nRuns := 0;
  PERS num nRunsSeen := 0;
  PROC main()
    Incr nRuns;
    nRunsSeen := nRuns;
    WHILE TRUE DO
      Incr nCount;
      WaitTime 0.05;
    ENDWHILE
  ENDPROC
ENDMODULE
)"));
    task.reset_pp();
    task.start();
    ASSERT_TRUE(eventually([&] { return num("nCount") >= 3; }));
    task.stop();
    ASSERT_TRUE(eventually([&] { return task.status().state == TaskState::stopped; }));
    const double at_stop = num("nCount");
    // 0.4 s simulated later: eight more counts if it ran.
    const double stopped_at_s = clock.now_s();
    ASSERT_TRUE(eventually([&] { return clock.now_s() >= stopped_at_s + 0.4; }));
    EXPECT_EQ(num("nCount"), at_stop);
    EXPECT_EQ(task.status().line, 10);  // stopped inside the loop

    task.start();  // continues: main is not entered again
    ASSERT_TRUE(eventually([&] { return num("nCount") >= at_stop + 2; }));
    EXPECT_EQ(num("nRunsSeen"), 1);

    task.stop();
    ASSERT_TRUE(eventually([&] { return task.status().state == TaskState::stopped; }));
    task.unload("T");  // the stopped program's frames keep their module alive
    EXPECT_THROW(task.start(), std::logic_error);  // no main any more
}

TEST_F(RapidTaskProgram, ResetPpRestoresVariablesButNotPersistents) {
    task.load(module_of(R"(MODULE T
  PERS num nCount := 0;
  VAR num nRuns := 0;
  PERS num nRunsSeen := 0;
  PROC main()
    Incr nRuns;
    nRunsSeen := nRuns;
    WHILE TRUE DO
      Incr nCount;
      WaitTime 0.05;
    ENDWHILE
  ENDPROC
ENDMODULE
)"));
    task.reset_pp();
    task.start();
    ASSERT_TRUE(eventually([&] { return num("nCount") >= 2; }));
    EXPECT_THROW(task.reset_pp(), std::logic_error);  // only while stopped
    task.stop();
    task.reset_pp();  // right after stop(): the thread parks at its next statement
    EXPECT_EQ(num("nRuns"), 0);
    const double count = num("nCount");
    EXPECT_GE(count, 2);
    task.start();
    ASSERT_TRUE(eventually([&] { return num("nCount") >= count + 2; }));
    EXPECT_EQ(num("nRunsSeen"), 1);  // VAR nRuns started from 0 again
}

TEST_F(RapidTaskProgram, StopInstructionAndExitAndExitCycle) {
    task.load(module_of(R"(MODULE T
  PERS num nStep := 0;
  VAR num nCycles := 0;
  PERS num nCyclesSeen := 0;
  PROC main()
    Incr nCycles;
    nCyclesSeen := nCycles;
    IF nCycles < 3 ExitCycle;
    nStep := 1;
    Stop;
    nStep := 2;
    EXIT;
    nStep := 3;
  ENDPROC
ENDMODULE
)"));
    task.reset_pp();
    task.start();
    ASSERT_TRUE(eventually([&] { return num("nStep") == 1 && task.status().state == TaskState::stopped; }));
    EXPECT_EQ(num("nCyclesSeen"), 3);  // ExitCycle keeps VAR values
    task.start();
    ASSERT_TRUE(eventually([&] { return num("nStep") == 2 && task.status().state == TaskState::stopped; }));
    const double stopped_at_s = clock.now_s();  // 0.2 s simulated later: still after EXIT
    ASSERT_TRUE(eventually([&] { return clock.now_s() >= stopped_at_s + 0.2; }));
    EXPECT_EQ(num("nStep"), 2);
    EXPECT_EQ(task.status().state, TaskState::stopped);
}

// stop(), start(), reset_pp() and the destructor in every order: nothing blocks.
TEST(RapidTaskLifecycle, NoOrderBlocks) {
    SimClock clock{50};
    MotionSimulator motion{clock};
    Io io;
    const std::string text = R"(MODULE T
  PERS num nCount := 0;
  PROC main()
    WHILE TRUE DO
      Incr nCount;
      WaitTime 0.01;
    ENDWHILE
  ENDPROC
ENDMODULE
)";
    {  // destroyed without start
        RapidTask task(clock, motion, io.task_io());
        task.load(module_of(text));
    }
    {  // stop right after start, then destroyed
        RapidTask task(clock, motion, io.task_io());
        task.load(module_of(text));
        task.start();
        task.stop();
        EXPECT_TRUE(eventually([&] { return task.status().state == TaskState::stopped; }));
    }
    {  // stop before any start, then start and stop again and again
        RapidTask task(clock, motion, io.task_io());
        task.load(module_of(text));
        task.stop();
        for (int i = 0; i < 20; ++i) {
            task.start();
            task.stop();
            if (i % 5 == 0) task.reset_pp();
        }
        task.start();
        ASSERT_TRUE(eventually([&] { return task.read_data("T", "nCount").num() >= 1; }));
        task.stop();
        ASSERT_TRUE(eventually([&] { return task.status().state == TaskState::stopped; }));
    }
    {  // destroyed while running and while waiting
        RapidTask task(clock, motion, io.task_io());
        task.load(module_of(text));
        task.start();
        ASSERT_TRUE(eventually([&] { return task.read_data("T", "nCount").num() >= 2; }));
    }
    {  // start without main
        RapidTask task(clock, motion, io.task_io());
        EXPECT_THROW(task.start(), std::logic_error);
    }
}

}  // namespace sim_rapid_task_program_test
