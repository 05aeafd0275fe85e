#include "drivers/abb/fcmain/fc_main_control.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

namespace fibrecell::drivers::abb {

std::string_view to_string(FcState s) {
    switch (s) {
        case FcState::idle: return "idle";
        case FcState::running: return "running";
        case FcState::paused: return "paused";
        case FcState::held: return "held";
        case FcState::completed: return "completed";
        case FcState::aborted: return "aborted";
        case FcState::rejected: return "rejected";
    }
    return "unknown";
}

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto poll_period = std::chrono::milliseconds(20);

int to_int(const std::string& text, const std::string& what) {
    try {
        return static_cast<int>(std::lround(std::stod(text)));
    } catch (const std::exception&) {
        throw FcRunError("FcMain " + what + " reads \"" + text + "\", not a number");
    }
}

// RWS returns RAPID string values with their quotes.
std::string unquote(const std::string& text) {
    if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
        return text.substr(1, text.size() - 2);
    return text;
}

std::string quote(const std::string& text) { return "\"" + text + "\""; }

std::string format_num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// Mastership held for the duration of a scope, released even when a write fails.
class Mastership {
  public:
    explicit Mastership(rws::RwsClient& rws) : rws_(rws) { rws_.request_mastership(); }
    ~Mastership() {
        try {
            rws_.release_mastership();
        } catch (const std::exception&) {  // the session may be gone; nothing is held then
        }
    }
    Mastership(const Mastership&) = delete;
    Mastership& operator=(const Mastership&) = delete;

  private:
    rws::RwsClient& rws_;
};

}  // namespace

FcMainControl::FcMainControl(rws::RwsClient& rws, std::string module)
    : rws_(rws), module_(std::move(module)) {}

void FcMainControl::upload_chunks(const std::string& job_dir, const std::vector<ChunkFile>& chunks) {
    for (const ChunkFile& c : chunks) rws_.upload_file(job_dir + "/" + c.file_name, c.text);
}

void FcMainControl::ensure_running() {
    const auto modules = rws_.modules();
    const bool loaded = std::any_of(modules.begin(), modules.end(), [&](const rws::ModuleInfo& m) {
        return m.name == module_;
    });
    if (!loaded)
        throw FcRunError("the resident module " + module_ + " is not loaded in the task on " +
                         rws_.endpoint() + " (install it: docs/irc5-setup.md)");
    const rws::ControllerState ctrl = rws_.controller_state();
    if (ctrl != rws::ControllerState::motoron)
        throw FcRunError("the controller at " + rws_.endpoint() + " is " +
                         std::string(rws::to_string(ctrl)) + ", not motoron: switch the motors on");
    if (rws_.execution_state().state == rws::ExecutionState::running) return;
    {
        Mastership m(rws_);
        rws_.reset_program_pointer();
    }
    rws_.start_execution();
}

FcStatus FcMainControl::request_run(const FcRunRequest& request,
                                    std::chrono::milliseconds timeout) {
    {
        Mastership m(rws_);
        rws_.set_symbol(module_, "sFcJobDir", quote("HOME:/" + request.job_dir));
        rws_.set_symbol(module_, "nFcChunkCount", std::to_string(request.chunk_count));
        rws_.set_symbol(module_, "nFcFirstChunk", std::to_string(request.first_chunk));
        rws_.set_symbol(module_, "nFcHbTimeout", format_num(request.heartbeat_timeout_s));
        rws_.set_symbol(module_, "bFcRun", "TRUE");
    }
    const auto deadline = Clock::now() + timeout;
    while (read("bFcRun") == "TRUE") {
        if (Clock::now() > deadline)
            throw FcRunError("FcMain on " + rws_.endpoint() + " did not take the run request within " +
                             std::to_string(timeout.count()) + " ms (is RAPID running main?)");
        std::this_thread::sleep_for(poll_period);
    }
    FcStatus s = status();
    if (s.state == FcState::rejected)
        throw FcRunError("FcMain rejected the run: " + s.message);
    // FcMain clears a request it finds on its way into the cycle (a leftover of a reset): the
    // run did not start then, and saying so beats waiting for events that never come.
    if (s.state != FcState::running && s.state != FcState::paused)
        throw FcRunError("FcMain did not start the run (state " + std::string(to_string(s.state)) +
                         (s.message.empty() ? "" : ": " + s.message) + ")");
    return s;
}

FcStatus FcMainControl::status() {
    FcStatus s;
    const int state = to_int(read("nFcState"), "nFcState");
    if (state < 0 || state > static_cast<int>(FcState::rejected))
        throw FcRunError("FcMain nFcState is " + std::to_string(state) + ", not 0..6");
    s.state = static_cast<FcState>(state);
    s.chunk_now = to_int(read("nFcChunkNow"), "nFcChunkNow");
    s.chunk_done = to_int(read("nFcChunkDone"), "nFcChunkDone");
    s.barrier = to_int(read("nFcBarrier"), "nFcBarrier");
    s.message = unquote(read("sFcMessage"));
    return s;
}

std::string FcMainControl::read(const std::string& name) { return rws_.symbol(module_, name); }

}  // namespace fibrecell::drivers::abb
