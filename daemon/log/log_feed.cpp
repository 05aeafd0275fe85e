#include "daemon/log/log_feed.hpp"

#include "config/printable.hpp"

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <ctime>
#include <mutex>

namespace fibrecell::daemon::logs {

namespace {

class LogFeedSink final : public spdlog::sinks::base_sink<std::mutex> {
  public:
    void set_target(LogTarget target) {
        const std::lock_guard lock(mutex_);
        target_ = std::move(target);
    }

  protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {
        if (!target_) return;
        const auto t = std::chrono::system_clock::to_time_t(msg.time);
        std::tm utc{};
        gmtime_r(&t, &utc);
        char stamp[32];
        std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &utc);
        const auto level = spdlog::level::to_string_view(msg.level);
        target_({{"time", stamp},
                 {"level", std::string(level.data(), level.size())},
                 {"text", config::printable(std::string_view(msg.payload.data(), msg.payload.size()))}});
    }
    void flush_() override {}

  private:
    LogTarget target_;  // guarded by base_sink's mutex_
};

LogFeedSink& installed_sink() {
    // Once per process, on the default logger that config::setup_logging made.
    static const std::shared_ptr<LogFeedSink> sink = [] {
        auto s = std::make_shared<LogFeedSink>();
        s->set_level(spdlog::level::info);
        spdlog::default_logger()->sinks().push_back(s);
        return s;
    }();
    return *sink;
}

}  // namespace

void feed_log_to(LogTarget target) { installed_sink().set_target(std::move(target)); }

}  // namespace fibrecell::daemon::logs
