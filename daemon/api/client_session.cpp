#include "daemon/api/client_session.hpp"

#include <spdlog/spdlog.h>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>

#include <algorithm>

namespace fibrecell::api {

namespace {

// Input still arriving after we decided to close is read and dropped for at most this long, so
// that a client blocked writing an oversized request gets to read our answer.
constexpr auto kDrainTime = std::chrono::seconds(2);
constexpr std::size_t kMaxBuffersPerWrite = 64;

std::chrono::nanoseconds interval_of(double rate_hz) {
    return std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / rate_hz));
}

}  // namespace

ClientSession::ClientSession(std::shared_ptr<ServerCore> core, Socket socket, std::uint64_t id,
                             Transport transport, std::string peer, std::string user)
    : core_(std::move(core)),
      socket_(std::move(socket)),
      id_(id),
      transport_(transport),
      peer_(std::move(peer)),
      user_(std::move(user)),
      // The socket's mode or the dashboard's login decided already; TCP calls server.auth.
      authenticated_(transport != Transport::tcp),
      gate_(core_->strand, interval_of(core_->config.progress_rate_hz),
            [this](const Line& line) { send_notification(line); }),
      auth_timer_(core_->strand),
      idle_timer_(core_->strand),
      drain_timer_(core_->strand) {}

ClientSession::~ClientSession() = default;

void ClientSession::start() {
    if (!authenticated_) {
        auth_timer_.expires_after(core_->config.tcp.auth_timeout);
        auth_timer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
            if (ec || self->authenticated_ || self->closing_) return;
            self->core_->counters.auth_failures++;
            spdlog::warn("api.auth_timeout client={} peer={}", self->id_, self->peer_);
            self->send(error_response(
                nullptr, errc::unauthorized,
                "unauthorized: no server.auth within " +
                    std::to_string(self->core_->config.tcp.auth_timeout.count()) + " ms"));
            self->close_after_flush();
        });
    }
    arm_idle_timer();
    read_more();
}

void ClientSession::arm_idle_timer() {
    auto timeout = core_->config.idle_timeout;
    if (control_only_ && (timeout.count() == 0 || timeout > core_->config.control_idle_timeout))
        timeout = core_->config.control_idle_timeout;
    if (timeout.count() == 0) return;
    idle_timer_.expires_after(timeout);
    idle_timer_.async_wait([self = shared_from_this(), timeout](const boost::system::error_code& ec) {
        if (ec || self->closing_) return;
        // A subscriber is waiting for events, not idle (a slow one meets the queue limit).
        if (!self->topics_.empty() && !self->control_only_) {
            self->arm_idle_timer();  // idle again once it unsubscribes
            return;
        }
        self->core_->counters.closed_idle++;
        spdlog::info("api.client_idle client={} peer={}: no request for {} ms; closed", self->id_,
                     self->peer_, timeout.count());
        self->send(error_response(nullptr, errc::unavailable,
                                  "unavailable: no request for " + std::to_string(timeout.count()) +
                                      " ms (api.idle_timeout_s); closing the connection"));
        self->close_after_flush();
    });
}

void ClientSession::refuse(const nlohmann::json& error_response) {
    send(error_response);
    close_after_flush();
    read_more();
}

void ClientSession::set_progress_interval(std::chrono::nanoseconds interval) {
    gate_.set_interval(interval);
}

void ClientSession::shutdown() {
    close_after_flush();
}

// ---- reading -----------------------------------------------------------------------------------

void ClientSession::read_more() {
    if (closed_ || reading_ || (read_paused_ && !closing_)) return;
    reading_ = true;
    socket_.async_read_some(
        boost::asio::buffer(chunk_),
        boost::asio::bind_executor(
            core_->strand, [self = shared_from_this()](const boost::system::error_code& ec,
                                                       std::size_t n) { self->on_read(ec, n); }));
}

void ClientSession::on_read(const boost::system::error_code& ec, std::size_t n) {
    reading_ = false;
    if (closed_) return;
    if (ec) {
        close(ec == boost::asio::error::eof ? "closed by the client" : ec.message());
        return;
    }
    if (!closing_) {
        inbuf_.append(chunk_.data(), n);
        process_lines();
    }
    if (closed_) return;
    if (!closing_ && out_bytes_ > core_->config.max_client_queue_bytes / 2) {
        read_paused_ = true;  // resumed by on_write once the client has read its answers
        return;
    }
    read_more();  // while closing: input is read and dropped until EOF or the drain time
}

void ClientSession::process_lines() {
    const std::size_t limit = core_->config.max_request_bytes;
    std::size_t start = 0;
    while (!closing_ && !closed_) {
        const std::size_t nl = inbuf_.find('\n', std::max(start, scanned_));
        if (nl == std::string::npos) break;
        std::string_view line(inbuf_.data() + start, nl - start);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (line.size() > limit) {
            reject_oversized();
            return;
        }
        last_active_ = std::chrono::steady_clock::now();
        handle_line(line);
        arm_idle_timer();  // cancels the pending wait
        start = nl + 1;
    }
    if (closed_ || closing_) return;
    inbuf_.erase(0, start);
    scanned_ = inbuf_.size();
    if (inbuf_.size() > limit) reject_oversized();
}

void ClientSession::reject_oversized() {
    core_->counters.oversized++;
    spdlog::warn("api.request_too_large client={} peer={} limit_bytes={}", id_, peer_,
                 core_->config.max_request_bytes);
    inbuf_.clear();
    scanned_ = 0;
    send(error_response(nullptr, errc::too_large,
                        "too_large: a request line may have at most " +
                            std::to_string(core_->config.max_request_bytes) +
                            " bytes (api.max_request_bytes); closing the connection"));
    close_after_flush();
}

// ---- writing -----------------------------------------------------------------------------------

void ClientSession::send(const nlohmann::json& message) {
    if (message.contains("error")) core_->counters.errors++;
    enqueue(std::make_shared<const std::string>(to_line(message)));
}

void ClientSession::send_notification(const Line& line) {
    core_->counters.notifications_sent++;
    enqueue(line);
}

void ClientSession::enqueue(Line line) {
    if (closed_) return;
    // One message always fits, so a large answer to a patient client still goes out.
    if (!outq_.empty() && out_bytes_ + line->size() > core_->config.max_client_queue_bytes) {
        core_->counters.dropped_slow++;
        spdlog::warn("api.client_dropped client={} peer={} reason=slow queued_bytes={} limit={}",
                     id_, peer_, out_bytes_, core_->config.max_client_queue_bytes);
        close("slow client: outgoing queue over api.max_client_queue_bytes");
        return;
    }
    out_bytes_ += line->size();
    outq_.push_back(std::move(line));
    if (!writing_) write_more();
}

void ClientSession::write_more() {
    writing_ = true;
    write_count_ = std::min(outq_.size(), kMaxBuffersPerWrite);
    write_buffers_.clear();
    for (std::size_t i = 0; i < write_count_; ++i)
        write_buffers_.push_back(boost::asio::buffer(*outq_[i]));
    boost::asio::async_write(
        socket_, write_buffers_,
        boost::asio::bind_executor(
            core_->strand, [self = shared_from_this()](const boost::system::error_code& ec,
                                                       std::size_t) { self->on_write(ec); }));
}

void ClientSession::on_write(const boost::system::error_code& ec) {
    writing_ = false;
    if (closed_) return;
    if (ec) {
        close("write failed: " + ec.message());
        return;
    }
    for (std::size_t i = 0; i < write_count_; ++i) {
        out_bytes_ -= outq_.front()->size();
        outq_.pop_front();
    }
    if (read_paused_ && out_bytes_ <= core_->config.max_client_queue_bytes / 2) {
        read_paused_ = false;
        read_more();
    }
    if (!outq_.empty()) {
        write_more();
    } else if (closing_) {
        finish_closing();
    }
}

// ---- closing -----------------------------------------------------------------------------------

void ClientSession::close_after_flush() {
    if (closing_) return;
    closing_ = true;
    gate_.cancel();
    auth_timer_.cancel();
    idle_timer_.cancel();
    drain_timer_.expires_after(kDrainTime);
    drain_timer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
        if (!ec) self->close("closed after an error");
    });
    // Posted: answers to the line being processed are queued before we look at the queue.
    boost::asio::post(core_->strand, [self = shared_from_this()] {
        if (!self->closed_ && !self->writing_ && self->outq_.empty()) self->finish_closing();
    });
}

void ClientSession::finish_closing() {
    // Half-close: the client reads our last answer, then EOF; its remaining input is drained.
    boost::system::error_code ignored;
    socket_.shutdown(Socket::shutdown_send, ignored);
    read_more();
}

void ClientSession::close(const std::string& reason) {
    if (closed_) return;
    closed_ = true;
    closing_ = true;
    gate_.cancel();
    auth_timer_.cancel();
    idle_timer_.cancel();
    drain_timer_.cancel();
    boost::system::error_code ignored;
    socket_.shutdown(Socket::shutdown_both, ignored);
    socket_.close(ignored);
    core_->sessions.erase(id_);
    core_->counters.clients--;
    spdlog::debug("api.client_closed client={} peer={} reason={}", id_, peer_, reason);
}

}  // namespace fibrecell::api
