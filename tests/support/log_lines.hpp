#pragma once
// The log lines this process writes while the object lives (spdlog's default logger), for tests
// that wait on a line the code logs at the moment it acts ("robot_io.service_stalled ...").

#include "tests/support/eventually.hpp"

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::test {

class LogLines {
  public:
    LogLines() : sink_(std::make_shared<Sink>()), logger_(spdlog::default_logger()) {
        logger_->sinks().push_back(sink_);
    }
    ~LogLines() {
        auto& sinks = logger_->sinks();
        sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
    }
    LogLines(const LogLines&) = delete;
    LogLines& operator=(const LogLines&) = delete;

    // How many lines so far contain `text`.
    std::size_t count(std::string_view text) const {
        const auto lines = sink_->lines();
        return static_cast<std::size_t>(std::count_if(lines.begin(), lines.end(), [&](const std::string& l) {
            return l.find(text) != std::string::npos;
        }));
    }
    // Waits until `n` lines contain `text`.
    bool wait_for(std::string_view text, std::size_t n = 1,
                  std::chrono::milliseconds timeout = eventually_timeout) const {
        return eventually([&] { return count(text) >= n; }, timeout);
    }

  private:
    class Sink : public spdlog::sinks::base_sink<std::mutex> {
      public:
        std::vector<std::string> lines() {
            std::lock_guard lock(mutex_);
            return lines_;
        }

      protected:
        void sink_it_(const spdlog::details::log_msg& msg) override {
            lines_.emplace_back(msg.payload.data(), msg.payload.size());
        }
        void flush_() override {}

      private:
        std::vector<std::string> lines_;
    };

    std::shared_ptr<Sink> sink_;
    std::shared_ptr<spdlog::logger> logger_;
};

}  // namespace fibrecell::test
