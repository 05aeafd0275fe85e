#pragma once
// Internal: one connection (Unix or TCP) of the ApiServer. Reads newline-delimited JSON-RPC,
// dispatches it (client_dispatch.cpp), writes answers and notifications through one outgoing
// queue, and holds the connection's authentication and subscriptions. Everything runs on the
// server's strand; async operations keep the session alive through shared_from_this.

#include "daemon/api/api_event.hpp"
#include "daemon/api/call_context.hpp"
#include "daemon/api/json_rpc.hpp"
#include "daemon/api/latest_only_gate.hpp"
#include "daemon/api/responder.hpp"
#include "daemon/api/server_core.hpp"

#include <boost/asio/generic/stream_protocol.hpp>
#include <boost/asio/steady_timer.hpp>

#include <array>
#include <deque>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::api {

class ClientSession : public std::enable_shared_from_this<ClientSession> {
  public:
    using Socket = boost::asio::generic::stream_protocol::socket;
    using Line = std::shared_ptr<const std::string>;

    ClientSession(std::shared_ptr<ServerCore> core, Socket socket, std::uint64_t id,
                  Transport transport, std::string peer, std::string user);
    ~ClientSession();

    void start();
    // Admitted into the reserved capacity: only control methods, and a short idle timeout.
    void restrict_to_control() { control_only_ = true; }
    // Answers `error_response` once and closes (the server is full).
    void refuse(const nlohmann::json& error_response);
    // A published event: sent if this client subscribed to its topic.
    void deliver(const std::string& topic, const std::string& method, Delivery delivery,
                 const Line& line);
    void shutdown();                        // queued answers go out, then the connection closes
    void close(const std::string& reason);  // now, without flushing
    void set_progress_interval(std::chrono::nanoseconds interval);

    std::uint64_t id() const { return id_; }
    const std::string& peer() const { return peer_; }
    // For the server's choice of whom to close when it is full (api_server.cpp).
    bool closing() const { return closing_; }
    bool unauthenticated_tcp() const { return transport_ == Transport::tcp && !authenticated_; }
    bool busy() const { return in_flight_ > 0; }  // a call of it not answered yet
    std::chrono::steady_clock::time_point last_active() const { return last_active_; }

  private:
    // The answers to one incoming line: one slot, or one per batch entry.
    struct PendingReply {
        std::weak_ptr<ClientSession> session;
        std::vector<std::optional<nlohmann::json>> slots;  // nullopt: a notification, no answer
        std::size_t remaining = 0;
        bool batch = false;
    };
    static void complete(const std::shared_ptr<PendingReply>& reply, std::size_t slot,
                         std::optional<nlohmann::json> response);

    // Reading and framing (client_session.cpp).
    void read_more();
    void on_read(const boost::system::error_code& ec, std::size_t n);
    void process_lines();
    void reject_oversized();

    // Protocol (client_dispatch.cpp).
    void handle_line(std::string_view line);
    void dispatch(nlohmann::json&& element, const std::shared_ptr<PendingReply>& reply,
                  std::size_t slot);
    Responder make_responder(const RpcRequest& request, const std::shared_ptr<PendingReply>& reply,
                             std::size_t slot);
    void authenticate(const RpcRequest& request, const Responder& responder);
    nlohmann::json change_subscriptions(const RpcRequest& request, bool subscribe);
    bool subscribed(const std::string& topic) const;

    // Writing (client_session.cpp).
    void send(const nlohmann::json& message);
    void send_notification(const Line& line);
    void enqueue(Line line);
    void write_more();
    void on_write(const boost::system::error_code& ec);
    void close_after_flush();
    void finish_closing();
    void arm_idle_timer();  // at the start and after every request line

    std::shared_ptr<ServerCore> core_;
    Socket socket_;
    const std::uint64_t id_;
    const Transport transport_;
    const std::string peer_;
    const std::string user_;  // CallContext::user

    std::array<char, 64 * 1024> chunk_{};
    std::string inbuf_;
    std::size_t scanned_ = 0;  // inbuf_[0, scanned_) holds no '\n'
    bool reading_ = false;
    bool read_paused_ = false;  // the client leaves our answers unread: stop taking requests

    std::deque<Line> outq_;
    std::size_t out_bytes_ = 0;
    std::vector<boost::asio::const_buffer> write_buffers_;
    std::size_t write_count_ = 0;
    bool writing_ = false;

    bool authenticated_;
    bool auth_failed_ = false;  // one try per connection, batched or not
    bool control_only_ = false;
    bool closing_ = false;  // no more requests: flush, half-close, drain the input, close
    std::size_t in_flight_ = 0;  // request lines not answered yet
    std::chrono::steady_clock::time_point last_active_ = std::chrono::steady_clock::now();  // connect, request
    bool closed_ = false;
    std::set<std::string, std::less<>> topics_;
    LatestOnlyGate gate_;
    boost::asio::steady_timer auth_timer_;
    boost::asio::steady_timer idle_timer_;
    boost::asio::steady_timer drain_timer_;
};

}  // namespace fibrecell::api
