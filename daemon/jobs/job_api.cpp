#include "daemon/jobs/job_api.hpp"

#include "daemon/api/params.hpp"

#include <limits>

namespace fibrecell::daemon::jobs {

std::int64_t job_id_param(const nlohmann::json& params, const api::CallContext& ctx) {
    api::ParamReader p(ctx.method, params);
    if (!p.has("job")) p.fail("job", "is required (a job id)");
    const std::int64_t id = p.integer_or("job", 0, 1, std::numeric_limits<std::int64_t>::max());
    p.finish();
    return id;
}

}  // namespace fibrecell::daemon::jobs
