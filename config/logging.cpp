#include "config/logging.hpp"

#include "config/printable.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <memory>

namespace fibrecell::config {
namespace {

// %* : the message with its control characters escaped (config/printable.hpp). Every log line is
// one line whatever a user put into a name or a file.
class PrintableMessage : public spdlog::custom_flag_formatter {
  public:
    void format(const spdlog::details::log_msg& msg, const std::tm&,
                spdlog::memory_buf_t& dest) override {
        const std::string text =
            printable(std::string_view(msg.payload.data(), msg.payload.size()));
        dest.append(text.data(), text.data() + text.size());
    }
    std::unique_ptr<custom_flag_formatter> clone() const override {
        return std::make_unique<PrintableMessage>();
    }
};

}  // namespace

void setup_logging(const std::string& level) {
    // The environment wins, so one run can be made verbose without touching configuration.
    const char* env = std::getenv("FIBRECELL_LOG");
    const std::string chosen = env && *env ? env : level.empty() ? "info" : level;
    // Once per process; a second call (a reload) changes the level only.
    auto logger = spdlog::get("fibrecell");
    if (!logger) logger = spdlog::stderr_color_mt("fibrecell");
    auto formatter = std::make_unique<spdlog::pattern_formatter>();
    formatter->add_flag<PrintableMessage>('*').set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %*");
    logger->set_formatter(std::move(formatter));
    logger->set_level(spdlog::level::from_str(chosen));
    spdlog::set_default_logger(logger);
}

}  // namespace fibrecell::config
