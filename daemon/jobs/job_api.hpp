#pragma once
// What the job.* methods share, whichever component answers them: the store's refusals as API
// errors, and the `job` parameter.

#include "daemon/api/api_error.hpp"
#include "daemon/api/call_context.hpp"
#include "daemon/jobs/job_store.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <system_error>

namespace fibrecell::daemon::jobs {

// Runs f, mapping the job store's refusals to API errors (not found, conflict, a state that could
// not be written); anything else is the caller's business.
template <class F>
auto as_api(F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const JobNotFound& e) {
        throw api::ApiError::not_found(e.what());
    } catch (const JobConflict& e) {
        throw api::ApiError::conflict(e.what());
    } catch (const StateWriteError& e) {
        throw api::ApiError::unavailable(std::string("unavailable: ") + e.what());  // a full disk
    } catch (const std::system_error& e) {
        // A job's files that could not be written (a full disk, an I/O error): nothing was
        // stored, and another try may succeed once there is room.
        throw api::ApiError::unavailable(std::string("unavailable: not stored: ") + e.what());
    }
}

// The call's `job` (a job id), the only parameter; "is required" when it is missing.
std::int64_t job_id_param(const nlohmann::json& params, const api::CallContext& ctx);

}  // namespace fibrecell::daemon::jobs
