#pragma once
// The service's side of the resident main module FcMain (drivers/abb/rapid/FcMain.mod) over RWS:
// upload a job's chunk modules into the job folder, make sure FcMain runs, hand it a run request
// through its PERS job parameters, and read its status. The motion-synchronous part (events,
// barriers, pause, abort, heartbeats) goes over Modbus (robot_io_link.hpp), not through here.
//
//   FcMainControl fc(rws);
//   fc.upload_chunks("fibrecell/job", chunks);          // HOME:/fibrecell/job/FcChunk0001.mod ...
//   fc.ensure_running();                                 // FcMain loaded, motors on, RAPID running
//   FcStatus s = fc.request_run({.job_dir = "fibrecell/job", .chunk_count = 8}, 5s);

#include "drivers/abb/rws/rws_client.hpp"

#include <chrono>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::drivers::abb {

// nFcState.
enum class FcState { idle = 0, running, paused, held, completed, aborted, rejected };
std::string_view to_string(FcState s);

struct FcStatus {
    FcState state = FcState::idle;
    int chunk_now = 0;   // nFcChunkNow: chunk being executed (0 when none)
    int chunk_done = 0;  // nFcChunkDone: last chunk completed (resume at chunk_done + 1)
    int barrier = 0;     // nFcBarrier: barrier number waited for last
    std::string message; // sFcMessage: why the last run was rejected or stopped
};

struct FcRunRequest {
    std::string job_dir = "fibrecell/job";  // relative to HOME:
    int chunk_count = 0;                    // FcChunk0001 .. FcChunk<count>
    int first_chunk = 1;                    // > 1 to resume a job at that chunk
    double heartbeat_timeout_s = 1.0;       // FcMain holds the robot after this long without one
};

struct ChunkFile {
    std::string file_name;  // "FcChunk0001.mod"
    std::string text;
};

// FcMain refused the run request (sFcMessage says why) or did not answer it in time.
class FcRunError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class FcMainControl {
  public:
    // `rws` must outlive this object. `module`: the resident module's name in T_ROB1.
    explicit FcMainControl(rws::RwsClient& rws, std::string module = "FcMain");

    // PUTs every chunk to HOME:/<job_dir>/<file_name>. Throws rws::RwsError.
    void upload_chunks(const std::string& job_dir, const std::vector<ChunkFile>& chunks);

    // FcMain loaded (otherwise FcRunError: install it, docs/irc5-setup.md), motors on (otherwise
    // FcRunError), and RAPID executing: when stopped, the program pointer is reset to main (with
    // mastership) and execution started. Throws rws::RwsError for link problems.
    void ensure_running();

    // Writes sFcJobDir, nFcChunkCount, nFcFirstChunk, nFcHbTimeout, then bFcRun := TRUE (holding
    // mastership for the writes), and waits until FcMain took the request (bFcRun back to FALSE).
    // Returns the status when the run started; throws FcRunError with FcMain's reason when it was
    // rejected, or when it did not answer within `timeout`. The service's heartbeat must already
    // be running (FcMain rejects a run without it).
    FcStatus request_run(const FcRunRequest& request, std::chrono::milliseconds timeout);

    FcStatus status();

  private:
    std::string read(const std::string& name);
    rws::RwsClient& rws_;
    std::string module_;
};

}  // namespace fibrecell::drivers::abb
