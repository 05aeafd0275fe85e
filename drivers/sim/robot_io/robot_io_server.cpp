#include "drivers/sim/robot_io/robot_io_server.hpp"

#include "config/thread_priority.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"

#include <arpa/inet.h>
#include <modbus.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

namespace fibrecell::drivers::sim {

// The map and its errors are the driver's (drivers/abb/modbus): the coupler serves what the link reads.
using abb::is_bit_table;
using abb::ModbusAddress;
using abb::ModbusTable;
using abb::RobotIoConfig;
using abb::RobotIoError;
using abb::RobotIoMap;

namespace {

using Clock = std::chrono::steady_clock;

std::string errno_text(int err) {
    return std::strerror(err);
}

// Registers (or, for bit tables, bits) a table needs so that every mapped address exists.
struct TableSizes {
    int coils = 0, discrete_inputs = 0, holding_registers = 0, input_registers = 0;
};

TableSizes table_sizes(const RobotIoMap& m, bool two_view) {
    TableSizes t;
    auto need = [&](const ModbusAddress& a) {
        int& n = a.table == ModbusTable::coil               ? t.coils
                 : a.table == ModbusTable::discrete_input   ? t.discrete_inputs
                 : a.table == ModbusTable::holding_register ? t.holding_registers
                                                            : t.input_registers;
        n = std::max(n, a.address + 1);
    };
    for (const ModbusAddress* a :
         {&m.event_number, &m.barrier_number, &m.robot_running, &m.heartbeat_in, &m.barrier_release,
          &m.pause_request, &m.abort_request, &m.heartbeat_out})
        need(*a);
    if (m.chunk_ready) need(*m.chunk_ready);
    if (two_view) {
        const int out_words = std::max(t.holding_registers, (t.coils + 15) / 16);
        const int in_words = std::max(t.input_registers, (t.discrete_inputs + 15) / 16);
        t.holding_registers = out_words;
        t.coils = std::min(out_words * 16, 65536);
        t.input_registers = in_words;
        t.discrete_inputs = std::min(in_words * 16, 65536);
    }
    return t;
}

class Fd {
  public:
    Fd() = default;
    explicit Fd(int fd) : fd_(fd) {}
    Fd(Fd&& o) noexcept : fd_(o.release()) {}
    Fd& operator=(Fd&& o) noexcept {
        reset(o.release());
        return *this;
    }
    ~Fd() { reset(); }
    int get() const { return fd_; }
    explicit operator bool() const { return fd_ >= 0; }
    int release() { return std::exchange(fd_, -1); }
    void reset(int fd = -1) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = fd;
    }

  private:
    int fd_ = -1;
};

// Closes with a reset (RST) instead of an orderly shutdown, like a device that lost power.
void abort_connection(Fd& fd) {
    linger lg{1, 0};
    ::setsockopt(fd.get(), SOL_SOCKET, SO_LINGER, &lg, sizeof lg);
    fd.reset();
}

}  // namespace

struct RobotIoServer::Impl {
    const RobotIoMap map;
    const RobotIoServerOptions opt;
    int bound_port = 0;
    sockaddr_in bind_addr{};

    mutable std::mutex mu;  // the mapping, commands, flags, stats
    mutable std::condition_variable changed;
    modbus_mapping_t* mapping = nullptr;
    ServiceCommands cmds;
    RobotIoServerStats st;
    std::function<void(const ServiceCommands&)> commands_cb;
    bool answering = true;
    int torn_reads_left = 0;
    std::uint16_t torn_value = 0;
    bool hb_running = true;
    bool stop = false;
    bool exited = false;  // the server thread has returned
    std::uint64_t drop_requested = 0, drop_done = 0;
    std::uint64_t refuse_requested = 0, refuse_done = 0;
    Clock::duration refuse_for{};

    // Server thread only.
    modbus_t* ctx = nullptr;  // framing only: never connects nor listens
    Fd listener;
    Fd wake_fd;
    std::vector<Fd> clients;
    Clock::time_point reopen_at{};
    bool listener_closed = false;
    Clock::time_point next_hb_toggle{};
    std::thread thread;

    Impl(RobotIoMap m, RobotIoServerOptions o) : map(std::move(m)), opt(std::move(o)) {
        RobotIoConfig check;
        check.map = map;
        validate(check);
        const TableSizes t = table_sizes(map, opt.two_view);
        mapping =
            modbus_mapping_new(t.coils, t.discrete_inputs, t.holding_registers, t.input_registers);
        if (!mapping) throw RobotIoError("robot_io server: cannot allocate the Modbus mapping");
        bind_addr.sin_family = AF_INET;
        bind_addr.sin_port = htons(static_cast<std::uint16_t>(opt.port));
        if (::inet_pton(AF_INET, opt.bind_address.c_str(), &bind_addr.sin_addr) != 1) {
            modbus_mapping_free(mapping);
            throw RobotIoError("robot_io server: '" + opt.bind_address +
                               "' is not an IPv4 address");
        }
        try {
            std::string err = open_listener();
            if (!err.empty()) throw RobotIoError("robot_io server: " + err);
            sockaddr_in actual{};
            socklen_t len = sizeof actual;
            ::getsockname(listener.get(), reinterpret_cast<sockaddr*>(&actual), &len);
            bound_port = ntohs(actual.sin_port);
            bind_addr.sin_port = actual.sin_port;  // a re-opened listener takes the same port
            wake_fd = Fd(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK));
            if (!wake_fd) throw RobotIoError("robot_io server: eventfd: " + errno_text(errno));
            ctx = modbus_new_tcp("127.0.0.1", bound_port);
            if (!ctx) throw RobotIoError("robot_io server: cannot create a Modbus context");
            modbus_set_byte_timeout(ctx, 0, 200000);
            modbus_set_indication_timeout(ctx, 0, 200000);
        } catch (...) {
            modbus_mapping_free(mapping);
            throw;
        }
        next_hb_toggle = Clock::now() + opt.robot_heartbeat_period;
        thread = std::thread([this] {
            config::make_thread_time_critical("sim.robot_io");
            run();
        });
    }

    ~Impl() {
        {
            std::lock_guard lock(mu);
            stop = true;
        }
        wake();
        thread.join();
        clients.clear();
        listener.reset();
        modbus_set_socket(ctx, -1);
        modbus_free(ctx);
        modbus_mapping_free(mapping);
    }

    void wake() const {
        const std::uint64_t one = 1;
        [[maybe_unused]] const auto n = ::write(wake_fd.get(), &one, sizeof one);
    }

    std::string open_listener() {
        Fd s(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
        if (!s) return "socket: " + errno_text(errno);
        const int on = 1;
        ::setsockopt(s.get(), SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
        if (::bind(s.get(), reinterpret_cast<const sockaddr*>(&bind_addr), sizeof bind_addr) != 0)
            return "bind " + opt.bind_address + ":" + std::to_string(ntohs(bind_addr.sin_port)) +
                   ": " + errno_text(errno);
        if (::listen(s.get(), 16) != 0) return "listen: " + errno_text(errno);
        listener = std::move(s);
        return "";
    }

    // --- the process image (mu held) ----------------------------------------------------------

    // Copies word `w` of a two-view image from the view that changed to the other one.
    void sync_word(ModbusTable from, int w) {
        if (!opt.two_view || w < 0) return;
        const bool outputs = from == ModbusTable::coil || from == ModbusTable::holding_register;
        std::uint8_t* bits = outputs ? mapping->tab_bits : mapping->tab_input_bits;
        std::uint16_t* regs = outputs ? mapping->tab_registers : mapping->tab_input_registers;
        const int nb_regs = outputs ? mapping->nb_registers : mapping->nb_input_registers;
        const int nb_bits = outputs ? mapping->nb_bits : mapping->nb_input_bits;
        if (w >= nb_regs) return;
        if (is_bit_table(from)) {
            std::uint16_t v = 0;
            for (int k = 0; k < 16 && 16 * w + k < nb_bits; ++k)
                if (bits[16 * w + k]) v = static_cast<std::uint16_t>(v | (1u << k));
            regs[w] = v;
        } else {
            for (int k = 0; k < 16 && 16 * w + k < nb_bits; ++k)
                bits[16 * w + k] = static_cast<std::uint8_t>((regs[w] >> k) & 1u);
        }
    }

    void sync_all(ModbusTable from) {
        const bool outputs = from == ModbusTable::coil || from == ModbusTable::holding_register;
        const int words = outputs ? mapping->nb_registers : mapping->nb_input_registers;
        for (int w = 0; w < words; ++w) sync_word(from, w);
    }

    void write_signal(const ModbusAddress& a, std::uint16_t v) {
        switch (a.table) {
            case ModbusTable::coil:
                mapping->tab_bits[a.address] = v ? 1 : 0;
                sync_word(a.table, a.address / 16);
                return;
            case ModbusTable::discrete_input:
                mapping->tab_input_bits[a.address] = v ? 1 : 0;
                sync_word(a.table, a.address / 16);
                return;
            case ModbusTable::holding_register:
            case ModbusTable::input_register: {
                std::uint16_t& r = a.table == ModbusTable::holding_register
                                       ? mapping->tab_registers[a.address]
                                       : mapping->tab_input_registers[a.address];
                if (a.bit) {
                    const auto mask = static_cast<std::uint16_t>(1u << *a.bit);
                    r = static_cast<std::uint16_t>(v ? (r | mask) : (r & ~mask));
                } else {
                    r = v;
                }
                sync_word(a.table, a.address);
                return;
            }
        }
    }

    std::uint16_t read_signal(const ModbusAddress& a) const {
        switch (a.table) {
            case ModbusTable::coil:
                return mapping->tab_bits[a.address];
            case ModbusTable::discrete_input:
                return mapping->tab_input_bits[a.address];
            case ModbusTable::holding_register:
            case ModbusTable::input_register: {
                const std::uint16_t r = a.table == ModbusTable::holding_register
                                            ? mapping->tab_registers[a.address]
                                            : mapping->tab_input_registers[a.address];
                return a.bit ? static_cast<std::uint16_t>((r >> *a.bit) & 1u) : r;
            }
        }
        return 0;
    }

    // Re-reads the commands after a write request; true when one changed.
    bool refresh_commands(Clock::time_point now) {
        ServiceCommands c = cmds;
        c.release = read_signal(map.barrier_release);
        c.pause = read_signal(map.pause_request) != 0;
        c.abort = read_signal(map.abort_request) != 0;
        c.heartbeat = read_signal(map.heartbeat_out) != 0;
        c.chunk_ready = map.chunk_ready ? read_signal(*map.chunk_ready) : 0;
        if (c.heartbeat != cmds.heartbeat) {
            ++c.heartbeat_edges;
            c.last_heartbeat_edge = now;
        }
        const bool differs = c.release != cmds.release || c.pause != cmds.pause ||
                             c.abort != cmds.abort || c.heartbeat != cmds.heartbeat ||
                             c.chunk_ready != cmds.chunk_ready;
        cmds = c;
        return differs;
    }

    // Whether the request PDU `pdu` (function code first) reads the event_number register.
    bool reads_event_number(const std::uint8_t* pdu) const {
        const ModbusAddress& a = map.event_number;
        const int fc = pdu[0];
        const bool table = (fc == 0x03 && a.table == ModbusTable::holding_register) ||
                           (fc == 0x04 && a.table == ModbusTable::input_register);
        const int start = (pdu[1] << 8) | pdu[2];
        const int count = (pdu[3] << 8) | pdu[4];
        return table && a.address >= start && a.address < start + count;
    }

    // --- the thread ---------------------------------------------------------------------------

    void serve(std::size_t i) {
        std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
        modbus_set_socket(ctx, clients[i].get());
        const int rc = modbus_receive(ctx, query);
        if (rc == -1) {  // closed by the peer, or garbage
            spdlog::debug("robot_io_server.connection_closed {}", modbus_strerror(errno));
            clients[i].reset();
            return;
        }
        if (rc == 0) return;  // not for us
        std::function<void(const ServiceCommands&)> cb;
        ServiceCommands snapshot;
        bool notify = false;
        {
            std::lock_guard lock(mu);
            ++st.requests;
            if (!answering) return;
            const int h = modbus_get_header_length(ctx);
            const int fc = query[h];
            std::optional<std::uint16_t> restore;
            if (torn_reads_left > 0 && reads_event_number(query + h)) {
                --torn_reads_left;
                restore = read_signal(map.event_number);
                write_signal(map.event_number, torn_value);
            }
            const int sent = modbus_reply(ctx, query, rc, mapping);
            if (restore) write_signal(map.event_number, *restore);
            if (sent == -1) {
                spdlog::debug("robot_io_server.reply_failed {}", modbus_strerror(errno));
                clients[i].reset();
                return;
            }
            const bool coils_written = fc == 0x05 || fc == 0x0F;
            const bool regs_written = fc == 0x06 || fc == 0x10 || fc == 0x16 || fc == 0x17;
            if (coils_written || regs_written) {
                ++st.writes;
                sync_all(coils_written ? ModbusTable::coil : ModbusTable::holding_register);
                notify = refresh_commands(Clock::now());
                snapshot = cmds;
                cb = commands_cb;
            }
        }
        if (notify) {
            changed.notify_all();
            if (cb) cb(snapshot);
        }
    }

    void accept_all() {
        for (;;) {
            Fd c(::accept4(listener.get(), nullptr, nullptr, SOCK_CLOEXEC));
            if (!c) return;  // EAGAIN, or a connection that vanished
            const int on = 1;
            ::setsockopt(c.get(), IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
            std::lock_guard lock(mu);
            if (static_cast<int>(st.connections_open) >= opt.max_connections) continue;
            ++st.connections_accepted;
            ++st.connections_open;
            clients.push_back(std::move(c));
        }
    }

    void handle_commands(Clock::time_point now) {
        std::uint64_t drops = 0, refuses = 0;
        Clock::duration refuse = {};
        {
            std::lock_guard lock(mu);
            drops = drop_requested;
            refuses = refuse_requested;
            refuse = refuse_for;
        }
        if (drops == drop_done && refuses == refuse_done) return;
        if (refuses != refuse_done) {
            listener.reset();
            listener_closed = true;
            reopen_at = now + refuse;
            spdlog::info("robot_io_server.refusing port={} for_ms={}", bound_port,
                         std::chrono::duration_cast<std::chrono::milliseconds>(refuse).count());
        }
        if (drops != drop_done) {
            spdlog::info("robot_io_server.dropping port={} connections={}", bound_port,
                         clients.size());
            for (auto& c : clients) abort_connection(c);
        }
        {
            std::lock_guard lock(mu);
            drop_done = drops;
            refuse_done = refuses;
        }
        changed.notify_all();
    }

    void run() {
        std::vector<pollfd> fds;
        for (;;) {
            auto now = Clock::now();
            {
                std::lock_guard lock(mu);
                if (stop) break;
            }
            handle_commands(now);
            if (listener_closed && now >= reopen_at) {
                const std::string err = open_listener();
                if (err.empty()) {
                    listener_closed = false;
                    spdlog::info("robot_io_server.listening port={}", bound_port);
                } else {
                    reopen_at = now + std::chrono::milliseconds(20);
                    spdlog::warn("robot_io_server.reopen_failed {}", err);
                }
            }
            // The robot's heartbeat.
            bool hb_on = false;
            {
                std::lock_guard lock(mu);
                hb_on = hb_running && opt.robot_heartbeat_period.count() > 0;
                if (hb_on && now >= next_hb_toggle) {
                    write_signal(map.heartbeat_in, read_signal(map.heartbeat_in) ? 0 : 1);
                    next_hb_toggle += opt.robot_heartbeat_period;
                    if (next_hb_toggle < now) next_hb_toggle = now + opt.robot_heartbeat_period;
                }
            }
            // Drop closed clients.
            {
                std::lock_guard lock(mu);
                clients.erase(
                    std::remove_if(clients.begin(), clients.end(), [](const Fd& f) { return !f; }),
                    clients.end());
                st.connections_open = clients.size();
            }
            fds.clear();
            fds.push_back({wake_fd.get(), POLLIN, 0});
            if (listener) fds.push_back({listener.get(), POLLIN, 0});
            const std::size_t first_client = fds.size();
            for (const auto& c : clients) fds.push_back({c.get(), POLLIN, 0});
            Clock::time_point until = Clock::time_point::max();
            if (hb_on) until = std::min(until, next_hb_toggle);
            if (listener_closed) until = std::min(until, reopen_at);
            int timeout_ms = -1;
            if (until != Clock::time_point::max()) {
                const auto left =
                    std::chrono::ceil<std::chrono::milliseconds>(until - Clock::now());
                timeout_ms = static_cast<int>(std::max<long long>(0, left.count()));
            }
            const int n = ::poll(fds.data(), fds.size(), timeout_ms);
            if (n < 0) {
                if (errno == EINTR) continue;
                spdlog::error("robot_io_server.poll_failed {}", errno_text(errno));
                break;
            }
            if (fds[0].revents & POLLIN) {
                std::uint64_t v = 0;
                [[maybe_unused]] const auto r = ::read(wake_fd.get(), &v, sizeof v);
            }
            for (std::size_t k = first_client; k < fds.size(); ++k) {
                if (fds[k].revents == 0) continue;
                const std::size_t i = k - first_client;
                if (fds[k].revents & POLLNVAL) {
                    clients[i].release();
                    continue;
                }
                if (clients[i]) serve(i);
            }
            if (listener && first_client > 1 && (fds[1].revents & POLLIN)) accept_all();
        }
        {
            std::lock_guard lock(mu);
            exited = true;
        }
        changed.notify_all();
    }

    // Runs a fault-knob request on the server thread and waits for it.
    void request(std::uint64_t Impl::*requested, std::uint64_t Impl::*done) {
        std::unique_lock lock(mu);
        const std::uint64_t target = ++(this->*requested);
        wake();
        changed.wait(lock, [&] { return this->*done >= target || stop || exited; });
    }
};

RobotIoServer::RobotIoServer(RobotIoMap map, RobotIoServerOptions options)
    : impl_(std::make_unique<Impl>(std::move(map), std::move(options))) {
    spdlog::info("robot_io_server.listening {}:{} two_view={}", impl_->opt.bind_address,
                 impl_->bound_port, impl_->opt.two_view);
}

RobotIoServer::~RobotIoServer() = default;

int RobotIoServer::port() const {
    return impl_->bound_port;
}
const std::string& RobotIoServer::host() const {
    return impl_->opt.bind_address;
}

void RobotIoServer::set_event_number(std::uint16_t n) {
    std::lock_guard lock(impl_->mu);
    impl_->write_signal(impl_->map.event_number, n);
}

void RobotIoServer::set_barrier_number(std::uint16_t n) {
    std::lock_guard lock(impl_->mu);
    impl_->write_signal(impl_->map.barrier_number, n);
}

void RobotIoServer::set_running(bool on) {
    std::lock_guard lock(impl_->mu);
    impl_->write_signal(impl_->map.robot_running, on ? 1 : 0);
}

void RobotIoServer::toggle_robot_heartbeat() {
    std::lock_guard lock(impl_->mu);
    impl_->write_signal(impl_->map.heartbeat_in,
                        impl_->read_signal(impl_->map.heartbeat_in) ? 0 : 1);
}

void RobotIoServer::set_robot_heartbeat_running(bool on) {
    {
        std::lock_guard lock(impl_->mu);
        impl_->hb_running = on;
    }
    impl_->wake();
}

ServiceCommands RobotIoServer::commands() const {
    std::lock_guard lock(impl_->mu);
    return impl_->cmds;
}

bool RobotIoServer::wait_for_commands(const std::function<bool(const ServiceCommands&)>& pred,
                                      std::chrono::milliseconds timeout) const {
    std::unique_lock lock(impl_->mu);
    return impl_->changed.wait_for(lock, timeout, [&] { return pred(impl_->cmds); });
}

void RobotIoServer::on_commands(std::function<void(const ServiceCommands&)> f) {
    std::lock_guard lock(impl_->mu);
    impl_->commands_cb = std::move(f);
}

void RobotIoServer::drop_connections() {
    impl_->request(&Impl::drop_requested, &Impl::drop_done);
}

void RobotIoServer::refuse_connections_for(std::chrono::milliseconds d) {
    {
        std::lock_guard lock(impl_->mu);
        impl_->refuse_for = d;
    }
    impl_->request(&Impl::refuse_requested, &Impl::refuse_done);
}

void RobotIoServer::set_answering(bool on) {
    std::lock_guard lock(impl_->mu);
    impl_->answering = on;
}

void RobotIoServer::inject_torn_event_reads(std::uint16_t value, int reads) {
    std::lock_guard lock(impl_->mu);
    impl_->torn_value = value;
    impl_->torn_reads_left = reads;
}

RobotIoServerStats RobotIoServer::stats() const {
    std::lock_guard lock(impl_->mu);
    return impl_->st;
}

}  // namespace fibrecell::drivers::sim
