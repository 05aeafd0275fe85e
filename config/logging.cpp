#include "config/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdlib>

namespace fibrecell::config {

void setup_logging(const std::string& level) {
    std::string chosen = level;
    if (chosen.empty()) {
        const char* env = std::getenv("FIBRECELL_LOG");
        chosen = env ? env : "info";
    }
    auto logger = spdlog::stderr_color_mt("fibrecell");
    logger->set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %v");
    logger->set_level(spdlog::level::from_str(chosen));
    spdlog::set_default_logger(logger);
}

}  // namespace fibrecell::config
