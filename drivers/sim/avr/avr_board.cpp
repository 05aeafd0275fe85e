#include "drivers/sim/avr/avr_board.hpp"

#include "drivers/sim/avr/avr_firmware.hpp"
#include "drivers/sim/sim_pty.hpp"

#include <avr_adc.h>
#include <avr_extint.h>
#include <avr_ioport.h>
#include <avr_uart.h>
#include <sim_avr.h>
#include <sim_irq.h>

#include <nlohmann/json.hpp>

#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <deque>
#include <fstream>
#include <functional>
#include <future>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <vector>

#include <unistd.h>

namespace fibrecell::drivers::sim::avr {

namespace {

using Clock = std::chrono::steady_clock;

constexpr avr_io_addr_t ucsr0b_addr = 0xC1;  // ATmega2560 data space
constexpr avr_io_addr_t ucsr0a_addr = 0xC0;
constexpr int txen_bit = 3, udre_bit = 5;
constexpr std::size_t max_pending_out = 64 * 1024;  // what a USB-serial bridge would buffer
constexpr double thermal_period_s = 1e-3;
constexpr double duty_average_s = 1.0;  // the status's heater duty: a moving average this long
// The MCU runs this much of its time between two looks at the pty and the wall clock: the
// serial latency the simulator adds (up to one slice each way).
constexpr double slice_s = 250e-6;

// simavr's own messages: errors and warnings to stderr, the rest dropped.
extern "C" void simavr_log(avr_t*, const int level, const char* format, va_list ap) {
    if (level > LOG_WARNING) return;
    std::fputs("gt2560-avr: simavr: ", stderr);
    std::vfprintf(stderr, format, ap);
}

// The simulator paces itself; simavr's default sleep would usleep on top of that.
extern "C" void no_sleep(avr_t*, avr_cycle_count_t) {}

struct PinWire {
    char port;
    int bit;
    BoardPin pin;
};
constexpr PinWire pin_wires[] = {
    {'L', 6, BoardPin::e0_step}, {'L', 4, BoardPin::e0_dir}, {'G', 0, BoardPin::e0_enable},
    {'L', 0, BoardPin::e1_step}, {'L', 2, BoardPin::e1_dir}, {'L', 1, BoardPin::e1_enable},
    {'E', 4, BoardPin::heater0}, {'E', 5, BoardPin::heater1},
    {'B', 5, BoardPin::d11},     {'H', 4, BoardPin::fan},
};

}  // namespace

struct AvrBoard::Impl {
    explicit Impl(AvrBoardOptions options)
        : o(std::move(options)), pty(o.link_path),
          to_board(o.fault_seed), from_board(o.fault_seed + 1) {
        if (!o.edge_log.empty()) {
            edge_log.open(o.edge_log, std::ios::trunc);
            if (!edge_log) throw std::runtime_error("gt2560-avr: cannot write " + o.edge_log);
        }
        pins = std::make_unique<BoardPins>(o.pins, o.edge_log.empty() ? nullptr : &edge_log);
    }

    AvrBoardOptions o;
    SimPty pty;
    WireFaults to_board, from_board;
    std::ofstream edge_log;
    std::unique_ptr<BoardPins> pins;
    FirmwareImage image;           // kept while the core runs (it may point at its symbols)
    avr_t* mcu = nullptr;
    std::vector<avr_irq_t*> adc;   // ADC8, ADC9
    avr_irq_t* uart_in = nullptr;
    struct PinHook {
        Impl* board;
        BoardPin pin;
    };
    std::array<PinHook, std::size(pin_wires)> pin_hooks{};

    // Owned by the simulation thread.
    std::deque<std::uint8_t> pending_in;   // from the host, not yet in the UART
    std::string pending_out;               // from the firmware, not yet in the pty
    std::uint64_t out_overflow = 0;        // bytes lost because nobody read the port
    bool xoff = false;
    bool txen = false;
    bool alive = true;                     // not crashed or stopped
    std::string halt_reason;
    avr_cycle_count_t cycle_base = 0;      // cycles before the last reset (simavr restarts at 0)
    std::array<double, 2> temp_c{};
    std::array<double, 2> duty_avg{};
    Clock::time_point start = Clock::now();
    Clock::duration offset{};              // pauses and slips: real time the MCU did not run
    double slipped_s = 0;
    std::uint64_t behind_events = 0;
    Clock::time_point last_behind_report{};
    Clock::time_point paused_until{};
    bool paused = false;
    double paused_s = 0;
    int resets = 0;
    bool plugged = true;

    std::mutex mu;
    std::deque<std::function<void()>> tasks;
    std::atomic<bool> stop{false};
    std::thread thread;

    double sim_s() const {
        return static_cast<double>(cycle_base + mcu->cycle) / static_cast<double>(o.frequency_hz);
    }

    void load() {
        read_firmware(o.firmware, image);
        avr_global_logger_set(simavr_log);
        mcu = avr_make_mcu_by_name("atmega2560");
        if (!mcu) throw std::runtime_error("gt2560-avr: this simavr has no atmega2560 core");
        avr_init(mcu);
        avr_load_firmware(mcu, &image.f);
        mcu->frequency = o.frequency_hz;
        mcu->vcc = mcu->avcc = mcu->aref = 5000;  // mV
        mcu->sleep = no_sleep;
        mcu->log = LOG_WARNING;

        std::uint32_t flags = 0;
        avr_ioctl(mcu, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
        flags &= ~static_cast<std::uint32_t>(AVR_UART_FLAG_POLL_SLEEP | AVR_UART_FLAG_STDIO);
        avr_ioctl(mcu, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);

        // simavr polls a low-level-triggered external interrupt every few cycles while its pin is
        // low ("strict" level triggering), enabled or not: the heater pins PE4/PE5 are INT4/INT5,
        // and that polling took a whole core. The GT2560 uses none of INT0..7 as an interrupt.
        for (std::uint8_t i = 0; i < 8; ++i) avr_extint_set_strict_lvl_trig(mcu, i, 0);

        uart_in = avr_io_getirq(mcu, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
        avr_irq_register_notify(avr_io_getirq(mcu, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                                &Impl::on_uart_out, this);
        avr_irq_register_notify(avr_io_getirq(mcu, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON),
                                &Impl::on_xon, this);
        avr_irq_register_notify(avr_io_getirq(mcu, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF),
                                &Impl::on_xoff, this);
        avr_irq_register_notify(avr_iomem_getirq(mcu, ucsr0b_addr, nullptr, txen_bit),
                                &Impl::on_txen, this);
        for (std::size_t i = 0; i < std::size(pin_wires); ++i) {
            const PinWire& w = pin_wires[i];
            pin_hooks[i] = {this, w.pin};
            avr_irq_register_notify(avr_io_getirq(mcu, AVR_IOCTL_IOPORT_GETIRQ(w.port), w.bit),
                                    &Impl::on_pin, &pin_hooks[i]);
        }
        route_thermistors();
        temp_c.fill(o.hotend.ambient_c);
        start_thermal();
    }

    // simavr 1.6 keeps input voltages for ADC0..ADC7 only (adc_values[8]); a conversion of ADC8
    // or ADC9 reads past that array. The GT2560's thermistors are on ADC8/ADC9, so their mux
    // settings (MUX5:0 = 32, 33) are pointed at ADC6/ADC7's slots, which stock Marlin leaves
    // unread on this board, and the voltages are fed there.
    void route_thermistors() {
        avr_adc_t* converter = nullptr;
        for (avr_io_t* io = mcu->io_port; io; io = io->next)
            if (std::string_view(io->kind) == "adc") converter = reinterpret_cast<avr_adc_t*>(io);
        if (!converter) throw std::runtime_error("gt2560-avr: the atmega2560 core has no ADC");
        for (int h = 0; h < 2; ++h) {
            converter->muxmode[32 + h] = converter->muxmode[6 + h];
            adc.push_back(avr_io_getirq(mcu, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC6 + h));
        }
    }

    void start_thermal() {
        for (int h = 0; h < 2; ++h) raise_thermistor(h);
        avr_cycle_timer_register(mcu, period_cycles(), &Impl::on_thermal_tick, this);
    }

    // The thermistor's voltage on the hotend's ADC pin, to the nearest millivolt (simavr's unit).
    void raise_thermistor(int h) {
        avr_raise_irq(adc[h], static_cast<std::uint32_t>(std::lround(thermistor_millivolts(temp_c[h]))));
    }

    avr_cycle_count_t period_cycles() const {
        return static_cast<avr_cycle_count_t>(thermal_period_s * o.frequency_hz);
    }

    static void on_uart_out(avr_irq_t*, std::uint32_t value, void* param) {
        auto* b = static_cast<Impl*>(param);
        const auto byte = b->from_board.pass(static_cast<std::uint8_t>(value));
        if (!byte) return;
        if (b->pending_out.size() >= max_pending_out) {
            ++b->out_overflow;
            return;
        }
        b->pending_out.push_back(static_cast<char>(*byte));
    }
    static void on_xon(avr_irq_t*, std::uint32_t value, void* param) {
        if (value) static_cast<Impl*>(param)->xoff = false;
    }
    static void on_xoff(avr_irq_t*, std::uint32_t value, void* param) {
        static_cast<Impl*>(param)->xoff = value != 0;
    }
    // simavr 1.6 leaves UDRE clear when the transmitter comes back on: set it, as the chip does.
    static void on_txen(avr_irq_t*, std::uint32_t value, void* param) {
        auto* b = static_cast<Impl*>(param);
        const bool on = value != 0;
        if (on && !b->txen) b->mcu->data[ucsr0a_addr] |= 1u << udre_bit;
        b->txen = on;
    }
    static void on_pin(avr_irq_t*, std::uint32_t value, void* param) {
        const auto* hook = static_cast<const PinHook*>(param);
        hook->board->pins->edge(hook->pin, value != 0, hook->board->sim_s());
    }
    static avr_cycle_count_t on_thermal_tick(avr_t*, avr_cycle_count_t when, void* param) {
        auto* b = static_cast<Impl*>(param);
        const double t = b->sim_s();
        const double fan = b->pins->take_on_s(BoardPin::fan, t) / thermal_period_s;
        for (int h = 0; h < 2; ++h) {
            const double duty =
                b->pins->take_on_s(h == 0 ? BoardPin::heater0 : BoardPin::heater1, t) / thermal_period_s;
            b->duty_avg[h] += (duty - b->duty_avg[h]) * (thermal_period_s / duty_average_s);
            b->temp_c[h] = hotend_step(b->temp_c[h], duty, fan, thermal_period_s, b->o.hotend);
            b->raise_thermistor(h);
        }
        return when + b->period_cycles();
    }

    void reset_mcu() {
        const avr_cycle_count_t before = cycle_base + mcu->cycle;
        avr_reset(mcu);
        cycle_base = before - mcu->cycle;
        pins->reset(sim_s());
        xoff = false;
        txen = false;
        alive = true;
        halt_reason.clear();
        ++resets;
        start_thermal();
    }

    // Host -> board: the pty's bytes through the wire's faults into a queue; the UART takes them
    // as it has room (simavr paces them at the baud rate; a full firmware ring loses them there).
    void move_bytes() {
        if (pty.master() >= 0) {
            std::uint8_t buf[512];
            for (;;) {
                const ssize_t n = ::read(pty.master(), buf, sizeof buf);
                if (n <= 0) break;
                for (ssize_t i = 0; i < n; ++i)
                    if (const auto b = to_board.pass(buf[i])) pending_in.push_back(*b);
            }
            while (!pending_out.empty()) {
                const ssize_t n = ::write(pty.master(), pending_out.data(), pending_out.size());
                if (n <= 0) break;
                pending_out.erase(0, static_cast<std::size_t>(n));
            }
        } else {
            pending_out.clear();  // unplugged: nobody is there
        }
        while (!xoff && !pending_in.empty()) {
            avr_raise_irq(uart_in, pending_in.front());
            pending_in.pop_front();
        }
    }

    void run_tasks() {
        std::deque<std::function<void()>> now;
        {
            std::lock_guard lock(mu);
            now.swap(tasks);
        }
        for (auto& t : now) t();
    }

    // Runs the MCU for a slice of its time, then waits until the wall clock has
    // caught up. Behind by more than 5 ms, the MCU does not rush: the lag is written off.
    void slice() {
        const avr_cycle_count_t end =
            mcu->cycle + static_cast<avr_cycle_count_t>(slice_s * o.frequency_hz);
        while (alive && mcu->cycle < end) {
            const int state = avr_run(mcu);
            if (state == cpu_Crashed || state == cpu_Done) {
                alive = false;
                halt_reason = state == cpu_Crashed ? "crashed" : "stopped";
                std::fprintf(stderr, "gt2560-avr: the firmware %s at %.3f s (pc 0x%x)\n",
                             halt_reason.c_str(), sim_s(), static_cast<unsigned>(mcu->pc));
            }
        }
        const auto target =
            start + offset + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(sim_s()));
        const auto now = Clock::now();
        if (target > now) {
            std::this_thread::sleep_until(target);
        } else if (now - target > std::chrono::milliseconds(5)) {
            const auto lag = now - target;
            offset += lag;
            slipped_s += std::chrono::duration<double>(lag).count();
            ++behind_events;
            if (now - last_behind_report > std::chrono::seconds(1)) {
                last_behind_report = now;
                std::fprintf(stderr, "gt2560-avr: behind real time by %.1f ms at %.3f s "
                             "(%.3f s written off so far)\n",
                             std::chrono::duration<double, std::milli>(lag).count(), sim_s(), slipped_s);
            }
        }
    }

    void run() {
        auto flushed = Clock::now();
        while (!stop.load()) {
            run_tasks();
            move_bytes();
            if (edge_log.is_open() && Clock::now() - flushed > std::chrono::milliseconds(200)) {
                edge_log.flush();  // a reader sees the edges of a fifth of a second ago
                flushed = Clock::now();
            }
            if (paused) {
                if (Clock::now() < paused_until) {
                    std::this_thread::sleep_for(std::chrono::milliseconds(1));
                    continue;
                }
                paused = false;
            }
            if (!alive) {
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
                continue;
            }
            slice();
        }
    }

    // Runs `f` on the simulation thread between two slices and returns once it has run.
    void run_on_board(std::function<void()> f) {
        auto done = std::make_shared<std::promise<void>>();
        auto ran = done->get_future();
        {
            std::lock_guard lock(mu);
            tasks.push_back([f = std::move(f), done] {
                f();
                done->set_value();
            });
        }
        ran.get();
    }

    nlohmann::json status() const {
        nlohmann::json extruders = nlohmann::json::array();
        for (int e = 0; e < 2; ++e) {
            const ExtruderSteps& x = pins->extruder(e);
            extruders.push_back({{"steps", x.net_steps}, {"forward", x.forward},
                                 {"backward", x.backward}, {"while_disabled", x.while_disabled},
                                 {"mm", pins->extruded_mm(e)}, {"first_step_s", x.first_step_s},
                                 {"last_step_s", x.last_step_s},
                                 {"enabled", !pins->level(e == 0 ? BoardPin::e0_enable
                                                                  : BoardPin::e1_enable)}});
        }
        nlohmann::json hotends = nlohmann::json::array();
        for (int h = 0; h < 2; ++h)
            hotends.push_back({{"temp_c", temp_c[h]}, {"duty", duty_avg[h]},
                               {"heater_on", pins->level(h == 0 ? BoardPin::heater0 : BoardPin::heater1)}});
        nlohmann::json d11_edges = nlohmann::json::array();
        for (const PinEdge& e : pins->d11_edges()) d11_edges.push_back({e.t_s, e.level ? 1 : 0});
        const auto wire = [](const WireFaults& w) {
            const WireFaultCounts& c = w.counts();
            return nlohmann::json{{"bytes", c.bytes}, {"dropped", c.dropped}, {"flipped", c.flipped},
                                  {"lines_corrupted", c.lines_corrupted}};
        };
        return {
            {"sim_time_s", sim_s()},
            {"state", !alive ? halt_reason : paused ? "paused" : "running"},
            {"resets", resets},
            {"plugged", plugged},
            {"port", pty.port_path()},
            {"behind", {{"events", behind_events}, {"written_off_s", slipped_s}}},
            {"paused_s", paused_s},
            {"wire", {{"to_board", wire(to_board)}, {"from_board", wire(from_board)},
                      {"unread_out_bytes_lost", out_overflow}}},
            {"hotends", hotends},
            {"extruders", extruders},
            {"d11", {{"level", pins->level(BoardPin::d11) ? 1 : 0}, {"edges", d11_edges},
                     {"servo_pulse_us", pins->servo_pulse_us()}}},
            {"fan", pins->level(BoardPin::fan) ? 1 : 0},
        };
    }
};

AvrBoard::AvrBoard(AvrBoardOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
    impl_->load();
    impl_->pty.open();
    impl_->start = Clock::now();
    impl_->thread = std::thread([this] { impl_->run(); });
}

AvrBoard::~AvrBoard() {
    impl_->stop = true;
    if (impl_->thread.joinable()) impl_->thread.join();
    if (impl_->mcu) {
        avr_terminate(impl_->mcu);
        retire_core(impl_->mcu);
    }
}

std::string AvrBoard::port_path() const { return impl_->pty.port_path(); }

void AvrBoard::set_wire_faults(WireSide side, const WireFaultRates& rates) {
    impl_->run_on_board([b = impl_.get(), side, rates] {
        (side == WireSide::to_board ? b->to_board : b->from_board).set(rates);
    });
}

void AvrBoard::pause(double seconds) {
    impl_->run_on_board([b = impl_.get(), seconds] {
        const auto d = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
        b->paused = true;
        b->paused_until = Clock::now() + d;
        b->offset += d;  // the MCU's clock stood still too: no rush afterwards
        b->paused_s += seconds;
    });
}

void AvrBoard::unplug() {
    impl_->run_on_board([b = impl_.get()] {
        b->pty.close();
        b->plugged = false;
    });
}

void AvrBoard::replug() {
    impl_->run_on_board([b = impl_.get()] {
        if (b->plugged) return;
        b->pty.open();
        b->plugged = true;
    });
}

void AvrBoard::reset() {
    impl_->run_on_board([b = impl_.get()] { b->reset_mcu(); });
}

std::string AvrBoard::status_json() const {
    std::string json;
    impl_->run_on_board([&] {
        json = impl_->status().dump();
        if (impl_->edge_log.is_open()) impl_->edge_log.flush();  // a test reads it next
    });
    return json;
}

}  // namespace fibrecell::drivers::sim::avr
