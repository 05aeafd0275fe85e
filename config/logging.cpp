#include "config/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdlib>

namespace fibrecell::config {

void setup_logging(const std::string& level) {
    // The environment wins, so one run can be made verbose without touching configuration.
    const char* env = std::getenv("FIBRECELL_LOG");
    const std::string chosen = env && *env ? env : level.empty() ? "info" : level;
    auto logger = spdlog::stderr_color_mt("fibrecell");
    logger->set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %v");
    logger->set_level(spdlog::level::from_str(chosen));
    spdlog::set_default_logger(logger);
}

}  // namespace fibrecell::config
