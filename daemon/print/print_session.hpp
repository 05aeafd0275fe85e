#pragma once
// One print on the cell: pre-flight, the run on the robot, the sync engine, pause, resume, abort
// and the end. The service runs one at a time; tests run it against the simulated cell.
//
//   start():  every chunk read back with the RAPID reader, robot I/O link up, board active,
//             FcMain loaded and RAPID running, the chunks uploaded to HOME:/<job_dir>, both hotends heated (M109), the sync engine started,
//             then FcMain's run request (it needs the service heartbeat, which the link sends)
//   poll():   FcMain's status over RWS and the engine's; the phase follows them
//   pause()/resume(): the engine stops metering and sets the robot's pause request (FcMain:
//             StopMove); resume undoes both. After the robot was held on a lost heartbeat,
//             resume() re-arms FcMain first (a pause request that rises while the heartbeat is
//             back, then drops: FcMain.mod, FcOnResume) and restarts the engine after the last
//             confirmed event
//   abort():  the robot's abort request until FcMain reports aborted, the board's queue dropped
//
// Two tiers of failure: start() refuses with a PrintError naming the step and moves nothing;
// a fault while printing (board, robot link, FcMain stopping) makes the phase `faulted` with
// the reason; the job's data stays and resume() may go on from the last confirmed event.

#include "daemon/sync/sync_engine.hpp"
#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/fcmain/fc_main_control.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "drivers/abb/rws/rws_client.hpp"
#include "drivers/extruder/extruder_controller.hpp"
#include "drivers/marlin/marlin_link.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::print {

// The cell's devices, owned by the service; they outlive the session.
struct PrintLinks {
    drivers::abb::rws::RwsClient& rws;
    drivers::abb::RobotIoLink& robot_io;
    drivers::marlin::MarlinLink& board;
    drivers::ExtruderController& extruder;
};

struct PrintOptions {
    std::string job_dir = "fibrecell/job";  // HOME:-relative folder for the chunks
    double heartbeat_timeout_s = 1.0;       // FcMain holds the robot after this long without one
    std::chrono::milliseconds link_timeout{5000};         // robot I/O link up before the start
    std::chrono::milliseconds run_request_timeout{5000};  // FcMain takes the run request
    std::chrono::milliseconds heat_timeout{600000};       // M109 of both hotends (real time)
    bool heat_before_start = true;
    // Pre-flight check of every chunk with the project's RAPID reader, as FcMain's load will
    // build it: the controller's signal names (RobotSignals::all()) and the chunk line limit.
    std::vector<std::string> signals = drivers::abb::RobotSignals{}.all();
    std::size_t max_chunk_lines = 5000;
    sync::SyncOptions sync;                 // first_event > 1 resumes a print
    // The chunks given are FcChunk<first_chunk> .. FcChunk<chunk_count> of the job (a re-entry
    // runs the job from the interrupted chunk on); chunk_count 0: as many as given.
    int first_chunk = 1;
    int chunk_count = 0;
    // Resuming at a re-entry point: the tool the re-entered unit prints with, selected after the
    // heat-up (the board may have been reset since; its own head switch is behind the re-entry).
    std::optional<drivers::Head> resume_tool;
    // Re-entering a fibre path: the fibre still runs from the nozzle into the part; it is cut
    // (with the tool selected) before the robot lifts.
    bool cut_before_start = false;
};

enum class PrintPhase { idle, printing, paused, completed, aborted, faulted };
std::string_view to_string(PrintPhase p);

struct PrintStatus {
    PrintPhase phase = PrintPhase::idle;
    std::string reason;               // why faulted or aborted
    drivers::abb::FcStatus robot;     // as last read over RWS
    sync::SyncStatus sync;
};

class PrintError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class PrintSession {
  public:
    PrintSession(const drivers::abb::PrintProgram& program,
                 std::vector<drivers::abb::ChunkFile> chunks, PrintLinks links,
                 PrintOptions options = {});
    ~PrintSession();
    PrintSession(const PrintSession&) = delete;
    PrintSession& operator=(const PrintSession&) = delete;

    // The links' observers, forwarded by their owner (any thread, never block).
    void robot_event(const drivers::abb::EventCounterChange& change);
    void robot_link_state(const drivers::abb::RobotIoStateChange& change);
    void board_temperature(const drivers::marlin::TemperatureReport& report);
    // The engine's confirmed events, for the job journal (engine thread, in order).
    void on_event_done(std::function<void(const sync::EventDone&)> f);

    // Throws PrintError naming the failed step; nothing moves then.
    void start();
    void pause();
    // From paused, or from faulted once the links are back. Throws PrintError when it cannot.
    void resume();
    // Stops the robot (abort request until FcMain reports aborted, at most `timeout`) and drops
    // the board's queue. The phase becomes aborted.
    void abort(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));

    // Reads FcMain's status and the engine's and updates the phase.
    PrintStatus poll();
    // Polls every `period` until completed, aborted or faulted, or `timeout`; returns the phase.
    PrintPhase wait_until_done(std::chrono::milliseconds timeout,
                               std::chrono::milliseconds period = std::chrono::milliseconds(50));

  private:
    void check_chunks() const;
    void start_engine(std::int64_t first_event, std::optional<sync::ResumeFeed> resume_feed = {},
                      bool paused = false);
    sync::SyncStatus settled_engine_status() const;
    void fault(const std::string& reason);
    void rearm_after_hold();
    void end_previous_run();
    void reset_service_outputs();
    void wait_for_robot_heartbeat();

    const drivers::abb::PrintProgram& program_;
    std::vector<drivers::abb::ChunkFile> chunks_;
    PrintLinks links_;
    PrintOptions options_;
    drivers::abb::FcMainControl fc_;
    std::function<void(const sync::EventDone&)> on_done_;

    mutable std::mutex mu_;  // guards engine_, status_, earlier_shortfalls_
    std::unique_ptr<sync::SyncEngine> engine_;
    std::vector<sync::Shortfall> earlier_shortfalls_;  // of engines a resume replaced
    // Every engine's latency samples (result.json's cut_error_mm counts the whole print).
    std::shared_ptr<sync::EventTimings> timings_ =
        std::make_shared<sync::EventTimings>(options_.sync.timing_window);
    PrintStatus status_;
};

}  // namespace fibrecell::daemon::print
