#include "drivers/marlin/marlin_protocol.hpp"

#include <algorithm>
#include <utility>

namespace fibrecell::drivers::marlin {

std::string_view to_string(LinkFailure f) {
    switch (f) {
        case LinkFailure::none: return "none";
        case LinkFailure::firmware_reset: return "firmware_reset";
        case LinkFailure::firmware_halted: return "firmware_halted";
        case LinkFailure::emergency_stop: return "emergency_stop";
        case LinkFailure::resend_out_of_window: return "resend_out_of_window";
        case LinkFailure::resend_loop: return "resend_loop";
        case LinkFailure::ack_timeout: return "ack_timeout";
        case LinkFailure::silent: return "silent";
        case LinkFailure::heating_stalled: return "heating_stalled";
        case LinkFailure::link_lost: return "link_lost";
        case LinkFailure::aborted: return "aborted";
    }
    return "?";
}

MarlinProtocol::MarlinProtocol(ProtocolSettings settings, Hooks hooks)
    : settings_(settings), hooks_(std::move(hooks)) {
    settings_.window_lines = std::max(1, settings_.window_lines);
    if (settings_.resend_ok == ResendOk::always) resend_ok_known_ = true;
    if (settings_.resend_ok == ResendOk::never) resend_ok_known_ = false;
}

void MarlinProtocol::begin_session(std::int64_t first, Clock::time_point now) {
    lines_.clear();
    oks_owed_.clear();
    first_unacked_ = next_to_send_ = next_line_ = first;
    session_started_ = true;
    keepalive_seen_ = false;  // a new session may be a different firmware
    session_synced_ = false;
    last_rx_ = now;
    enqueue("M110", now);
}

std::int64_t MarlinProtocol::enqueue(std::string_view command, Clock::time_point now) {
    std::string cmd = strip_comment(command);
    if (cmd.empty()) throw LineError("empty G-code line '" + std::string(command) + "'");
    const std::int64_t line = next_line_;
    const bool reset = command_word(cmd) == "M110";
    // The reset always carries its own number (`N<k> M110 N<k>`) so that Marlin applies it on
    // receipt, not when it executes behind queued lines (docs/marlin-link.md, "Numbers and
    // checksums").
    if (reset) cmd = "M110 N" + std::to_string(line);
    Entry e{line, frame_line(line, cmd) + "\n", classify(cmd), reset, {}, {}};
    lines_.push_back(std::move(e));
    ++next_line_;
    pump(now);
    return line;
}

void MarlinProtocol::send_emergency(std::string_view command) {
    const std::string cmd = strip_comment(command);
    hooks_.write(cmd + "\n");
    ++stats_.lines_sent;
    if (command_word(cmd) == "M112") {
        fail(LinkFailure::emergency_stop, "M112 sent: the firmware halts and needs a reset");
        return;
    }
    // The line still passes through Marlin's queue and is answered with an ok there.
    oks_owed_.push_back({-1});
}

std::size_t MarlinProtocol::discard_unsent() {
    const std::size_t n = static_cast<std::size_t>(next_line_ - next_to_send_);
    lines_.erase(lines_.begin() + static_cast<std::ptrdiff_t>(in_flight()), lines_.end());
    next_line_ = next_to_send_;
    return n;
}

void MarlinProtocol::pump(Clock::time_point now) {
    if (failed() || awaiting_resend_ok_ || settling_ || probing_) return;
    while (next_to_send_ < next_line_) {
        Entry& e = entry(next_to_send_);
        const std::size_t flying = in_flight();
        if (flying > 0) {
            if (flying >= static_cast<std::size_t>(settings_.window_lines)) break;
            if (e.barrier || entry(first_unacked_).barrier) break;
            std::size_t bytes = e.framed.size();
            for (std::int64_t l = first_unacked_; l < next_to_send_; ++l) bytes += entry(l).framed.size();
            if (bytes > static_cast<std::size_t>(settings_.window_bytes)) break;
        }
        e.deadline_base = now;
        e.sent_at = now;
        ++next_to_send_;
        oks_owed_.push_back({e.line});
        ++stats_.lines_sent;
        hooks_.write(e.framed);
        if (failed()) return;
    }
}

void MarlinProtocol::on_line(std::string_view raw, Clock::time_point now) {
    if (failed()) return;
    last_rx_ = now;
    const Reply r = parse_reply(raw);
    if (r.kind == ReplyKind::empty) return;
    // The reset cut an `ok` short: the old firmware had taken that line before it went.
    if (r.kind == ReplyKind::start && (r.cut_line == "ok" || r.cut_line.starts_with("ok ")))
        on_line("ok", now);
    if (hooks_.observed) hooks_.observed(r);

    if (awaiting_resend_ok_) {
        awaiting_resend_ok_ = false;
        if (r.kind == ReplyKind::ok && !r.temperatures) {
            resend_ok_known_ = true;  // this firmware answers Resend with an ok: this is it
            pump(now);
            return;
        }
        resend_ok_known_ = false;
    }

    switch (r.kind) {
        case ReplyKind::ok: handle_ok(r, now); break;
        case ReplyKind::resend:
            if (!r.line) {
                fail(LinkFailure::resend_out_of_window, "unreadable resend request '" + r.text + "'");
                break;
            }
            handle_resend(*r.line, now);
            break;
        case ReplyKind::start:
            seen_start_ = true;
            if (session_started_)
                fail(LinkFailure::firmware_reset,
                     "the firmware sent 'start' during the session: it was reset and its line "
                     "numbering and queued commands are lost");
            break;
        case ReplyKind::error:
            if (r.fatal) fail(LinkFailure::firmware_halted, "firmware: " + r.text);
            break;
        case ReplyKind::line_error:
            request_is_new_ = r.text.find("Line Number is not") == std::string::npos;
            break;
        case ReplyKind::busy:
            keepalive_seen_ = true;
            if (in_flight() > 0) entry(first_unacked_).deadline_base = now;
            break;
        case ReplyKind::temperature:
            if (in_flight() > 0 && entry(first_unacked_).cls == CommandClass::heating)
                entry(first_unacked_).deadline_base = now;
            break;
        default: break;
    }
}

void MarlinProtocol::handle_ok(const Reply& r, Clock::time_point now) {
    (void)r;
    if (resend_oks_pending_ > 0) {
        --resend_oks_pending_;
        pump(now);
        return;
    }
    if (oks_owed_.empty()) {
        ++stats_.unexpected_oks;
        return;
    }
    const OkOwed owed = oks_owed_.front();
    oks_owed_.pop_front();
    if (owed.line < 0) return;  // an out-of-band command's ok
    ack_front(now);
    if (probing_) {
        // The line's ok was late, not lost, or the probe copy itself executed. If the original
        // was received too, the copy now draws "Resend: <line+1>": wait briefly to absorb it.
        probing_ = false;
        settling_ = true;
        settle_deadline_ = now + std::chrono::duration_cast<Clock::duration>(settings_.probe_settle);
    }
    pump(now);
}

void MarlinProtocol::handle_resend(std::int64_t line, Clock::time_point now) {
    ++stats_.resend_requests;
    const bool is_new = std::exchange(request_is_new_, false);
    if (resend_ok_known_) {
        if (*resend_ok_known_) ++resend_oks_pending_;
    } else {
        awaiting_resend_ok_ = true;
        resend_ok_deadline_ =
            now + std::chrono::duration_cast<Clock::duration>(settings_.resend_ok_wait);
    }

    if (settling_ && line == probe_line_ + 1) {  // the probe copy was rejected as a duplicate
        settling_ = false;
        ++stats_.resends_ignored;
        pump(now);
        return;
    }
    if (probing_ && line == probe_line_ + 1 && first_unacked_ == probe_line_) {
        // The firmware already holds the probed line and answered the copy before any ok: the
        // original ok was lost. Count it as acknowledged; nothing runs twice.
        probing_ = false;
        const auto it = std::find_if(oks_owed_.begin(), oks_owed_.end(),
                                     [&](const OkOwed& o) { return o.line == probe_line_; });
        if (it != oks_owed_.end()) oks_owed_.erase(it);
        ack_front(now);
        pump(now);
        return;
    }
    if (dedupe_budget_ > 0 && line == dedupe_line_ && !is_new) {
        --dedupe_budget_;
        ++stats_.resends_ignored;
        pump(now);
        return;
    }
    if (line == next_to_send_) {  // the firmware has everything we sent: nothing to resend
        ++stats_.resends_ignored;
        pump(now);
        return;
    }
    if (line < first_unacked_ || line > next_to_send_) {
        fail(LinkFailure::resend_out_of_window,
             "the firmware asked for line " + std::to_string(line) + " but only lines " +
                 std::to_string(first_unacked_) + ".." + std::to_string(next_to_send_ - 1) +
                 " are unacknowledged");
        return;
    }
    same_request_count_ = line == last_request_ ? same_request_count_ + 1 : 1;
    last_request_ = line;
    if (same_request_count_ > settings_.max_consecutive_resends) {
        fail(LinkFailure::resend_loop, "line " + std::to_string(line) + " requested " +
                                           std::to_string(same_request_count_) + " times in a row");
        return;
    }
    // Go back N once: every line from `line` on goes again. Lines already on the wire behind it
    // will each draw one more request for the same line; those are ignored.
    probing_ = false;
    dedupe_line_ = line;
    dedupe_budget_ = static_cast<int>(next_to_send_ - line - 1);
    oks_owed_.erase(std::remove_if(oks_owed_.begin(), oks_owed_.end(),
                                   [&](const OkOwed& o) { return o.line >= line; }),
                    oks_owed_.end());
    next_to_send_ = line;
    pump(now);
}

void MarlinProtocol::ack_front(Clock::time_point now) {
    (void)now;
    const Entry e = std::move(lines_.front());
    lines_.pop_front();
    ++first_unacked_;
    ++stats_.lines_acked;
    probes_ = 0;
    if (e.line != last_request_) same_request_count_ = 0;
    if (e.barrier) session_synced_ = true;
    if (hooks_.acked) hooks_.acked(e.line);
}

void MarlinProtocol::probe(Clock::time_point now) {
    Entry& f = entry(first_unacked_);
    f.deadline_base = now;
    probing_ = true;
    probe_line_ = f.line;
    ++probes_;
    ++stats_.lines_sent;
    // Re-sending the line with its own number is safe: if Marlin already has it, the copy fails
    // the sequence check and is never executed.
    hooks_.write(f.framed);
}

void MarlinProtocol::on_tick(Clock::time_point now) {
    if (failed()) return;
    if (awaiting_resend_ok_ && now >= resend_ok_deadline_) {
        awaiting_resend_ok_ = false;
        resend_ok_known_ = false;
        pump(now);
    }
    if (settling_ && now >= settle_deadline_) {
        settling_ = false;
        pump(now);
    }
    if (in_flight() == 0) return;
    Entry& f = entry(first_unacked_);
    if (now - std::max(last_rx_, f.sent_at) > settings_.silence_timeout) {
        fail(LinkFailure::silent, "nothing received for " +
                                      std::to_string(settings_.silence_timeout.count()) +
                                      " s while line " + std::to_string(f.line) + " was in flight");
        return;
    }
    if (f.cls == CommandClass::heating) {
        if (now - f.deadline_base > settings_.heating_liveness)
            fail(LinkFailure::heating_stalled,
                 "no busy or temperature line for " +
                     std::to_string(settings_.heating_liveness.count()) + " s during line " +
                     std::to_string(f.line));
        return;
    }
    if (now - f.deadline_base > timeout_for(f)) {
        ++stats_.timeouts;
        if (probes_ >= settings_.max_probes) {
            fail(LinkFailure::ack_timeout,
                 "no ok for line " + std::to_string(f.line) + " (" + std::string(to_string(f.cls)) +
                     ") after " + std::to_string(probes_) + " probes");
            return;
        }
        probe(now);
    }
}

void MarlinProtocol::on_link_lost(const std::string& detail) { fail(LinkFailure::link_lost, detail); }

void MarlinProtocol::fail(LinkFailure f, const std::string& detail) {
    if (failed()) return;
    failure_ = f;
    if (hooks_.failed) hooks_.failed(f, detail);
}

Seconds MarlinProtocol::timeout_for(const Entry& e) const {
    const auto kept_alive = [&](Seconds t) {
        return keepalive_seen_ ? std::min(t, settings_.keepalive_liveness) : t;
    };
    switch (e.cls) {
        case CommandClass::motion: return kept_alive(settings_.motion_timeout);
        case CommandClass::long_running: return kept_alive(settings_.long_timeout);
        case CommandClass::heating: return settings_.heating_liveness;
        case CommandClass::normal: break;
    }
    return settings_.ok_timeout;
}

}  // namespace fibrecell::drivers::marlin
