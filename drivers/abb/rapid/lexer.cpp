#include "drivers/abb/rapid/lexer.hpp"

#include <cctype>
#include <charconv>
#include <cstdio>
#include <system_error>

#include "drivers/abb/rapid/names.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace {

bool is_alpha(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) != 0;
}
bool is_digit(char c) {
    return c >= '0' && c <= '9';
}
bool is_word(char c) {
    return is_alpha(c) || is_digit(c) || c == '_';
}
bool is_hex(char c) {
    return std::isxdigit(static_cast<unsigned char>(c)) != 0;
}
bool is_ascii_text(unsigned char c) {
    return c == '\t' || c == '\n' || c == '\r' || (c >= 0x20 && c < 0x7f);
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

std::string hex_byte(unsigned char c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned>(c));
    return buf;
}

class Lexer {
  public:
    Lexer(std::string_view text, std::string_view file) : s_(text), file_(file) {}

    LexResult run() {
        check_bytes();
        read_header();
        out_.tokens.reserve(s_.size() / 3);
        while (pos_ < s_.size()) next();
        push(TokenKind::end, "", line_);
        return std::move(out_);
    }

  private:
    void report(Rule rule, std::size_t line, std::string message) {
        out_.diagnostics.push_back({std::string(file_), line, rule, std::move(message)});
    }

    void push(TokenKind kind, std::string text, std::size_t line, double number = 0) {
        Token t;
        t.kind = kind;
        t.keyword = kind == TokenKind::identifier && is_reserved_word(text);
        t.text = std::move(text);
        t.number = number;
        t.line = line;
        out_.tokens.push_back(std::move(t));
    }

    // Encoding and line ends, at most one report of each per line.
    void check_bytes() {
        std::size_t line = 1;
        std::size_t encoding_line = 0, ending_line = 0;
        if (s_.size() >= 3 && s_.substr(0, 3) == "\xEF\xBB\xBF") {
            report(Rule::encoding, 1,
                   "file starts with a UTF-8 byte order mark; RAPID files are plain ASCII");
            encoding_line = 1;
        }
        for (std::size_t i = 0; i < s_.size(); ++i) {
            const auto c = static_cast<unsigned char>(s_[i]);
            if (c == '\r' && (i + 1 >= s_.size() || s_[i + 1] != '\n') && ending_line != line) {
                report(Rule::line_ending, line,
                       "carriage return not followed by a line feed (only LF or CR LF line ends)");
                ending_line = line;
            }
            if (!is_ascii_text(c) && encoding_line != line) {
                report(Rule::encoding, line,
                       (c >= 0x80 ? "non-ASCII byte " : "control character ") + hex_byte(c));
                encoding_line = line;
            }
            if (c == '\n') ++line;
        }
        out_.line_count = line - ((s_.empty() || s_.back() == '\n') ? 1 : 0);
    }

    // The optional %%% ... %%% block before MODULE (RoboDK emits VERSION:1 / LANGUAGE:ENGLISH).
    void read_header() {
        std::size_t p = 0, line = 1;
        while (p < s_.size() && (s_[p] == ' ' || s_[p] == '\t' || s_[p] == '\r' || s_[p] == '\n')) {
            if (s_[p] == '\n') ++line;
            ++p;
        }
        if (s_.substr(p, 3) != "%%%") return;
        const std::size_t open_line = line;
        auto line_at = [&](std::size_t from) {
            const std::size_t nl = s_.find('\n', from);
            return s_.substr(from, nl == std::string_view::npos ? s_.size() - from : nl - from);
        };
        if (trim(line_at(p)) != "%%%") return;  // not a header line: let the parser complain
        p += line_at(p).size();
        while (p < s_.size()) {
            ++p;  // the '\n'
            ++line;
            if (p >= s_.size()) break;
            const std::string_view l = trim(line_at(p));
            p += line_at(p).size();
            if (l == "%%%") {
                pos_ = p;
                line_ = line;
                return;
            }
            if (!l.empty()) out_.header.emplace_back(l);
        }
        report(Rule::syntax, open_line, "header block '%%%' is not closed by a second '%%%' line");
        pos_ = s_.size();
        line_ = line;
    }

    void next() {
        const char c = s_[pos_];
        if (c == '\n') {
            ++line_;
            ++pos_;
        } else if (c == '!') {
            while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
        } else if (is_alpha(c)) {
            identifier();
        } else if (is_digit(c) || (c == '.' && pos_ + 1 < s_.size() && is_digit(s_[pos_ + 1]))) {
            number();
        } else if (c == '"') {
            string();
        } else if (!is_ascii_text(static_cast<unsigned char>(c)) || c == ' ' || c == '\t' ||
                   c == '\r') {
            ++pos_;  // blanks; bad bytes were reported by check_bytes()
        } else {
            punct();
        }
    }

    void identifier() {
        const std::size_t start = pos_;
        while (pos_ < s_.size() && is_word(s_[pos_])) ++pos_;
        std::string text(s_.substr(start, pos_ - start));
        if (text.size() > max_identifier_length)
            report(Rule::identifier_length, line_,
                   "identifier '" + text + "' is " + std::to_string(text.size()) +
                       " characters; at most " + std::to_string(max_identifier_length));
        push(TokenKind::identifier, std::move(text), line_);
    }

    void number() {
        const std::size_t start = pos_;
        double value = 0;
        bool ok = true;
        if (s_[pos_] == '0' && pos_ + 2 < s_.size() &&
            (s_[pos_ + 1] == 'x' || s_[pos_ + 1] == 'X' || s_[pos_ + 1] == 'o' ||
             s_[pos_ + 1] == 'O' || s_[pos_ + 1] == 'b' || s_[pos_ + 1] == 'B') &&
            is_hex(s_[pos_ + 2])) {
            const char kind =
                static_cast<char>(std::tolower(static_cast<unsigned char>(s_[pos_ + 1])));
            const int base = kind == 'x' ? 16 : kind == 'o' ? 8 : 2;
            pos_ += 2;
            const std::size_t digits = pos_;
            while (pos_ < s_.size() && is_hex(s_[pos_])) ++pos_;
            unsigned long long v = 0;
            const auto r = std::from_chars(s_.data() + digits, s_.data() + pos_, v, base);
            ok = r.ec == std::errc() && r.ptr == s_.data() + pos_;
            value = static_cast<double>(v);
        } else {
            while (pos_ < s_.size() && is_digit(s_[pos_])) ++pos_;
            if (pos_ < s_.size() && s_[pos_] == '.') {
                ++pos_;
                while (pos_ < s_.size() && is_digit(s_[pos_])) ++pos_;
            }
            if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
                std::size_t e = pos_ + 1;
                if (e < s_.size() && (s_[e] == '+' || s_[e] == '-')) ++e;
                if (e < s_.size() && is_digit(s_[e])) {
                    pos_ = e;
                    while (pos_ < s_.size() && is_digit(s_[pos_])) ++pos_;
                }
            }
            const auto r = std::from_chars(s_.data() + start, s_.data() + pos_, value);
            ok = r.ec == std::errc() && r.ptr == s_.data() + pos_;
        }
        std::string text(s_.substr(start, pos_ - start));
        if (pos_ < s_.size() && is_word(s_[pos_])) {
            while (pos_ < s_.size() && is_word(s_[pos_])) ++pos_;
            report(Rule::syntax, line_,
                   "malformed number '" + std::string(s_.substr(start, pos_ - start)) + "'");
            push(TokenKind::invalid, std::move(text), line_);
            return;
        }
        if (!ok) {
            report(Rule::syntax, line_, "invalid or out-of-range number '" + text + "'");
            push(TokenKind::invalid, std::move(text), line_);
            return;
        }
        push(TokenKind::number, std::move(text), line_, value);
    }

    void string() {
        ++pos_;  // opening quote
        std::string value;
        while (true) {
            if (pos_ >= s_.size() || s_[pos_] == '\n') {
                report(Rule::syntax, line_, "string is not closed on its line");
                push(TokenKind::invalid, std::move(value), line_);
                return;
            }
            const char c = s_[pos_];
            if (c == '"') {
                if (pos_ + 1 < s_.size() && s_[pos_ + 1] == '"') {
                    value += '"';
                    pos_ += 2;
                    continue;
                }
                ++pos_;
                break;
            }
            if (c == '\\' && pos_ + 1 < s_.size() && s_[pos_ + 1] == '\\') {
                value += '\\';
                pos_ += 2;
                continue;
            }
            if (c == '\\' && pos_ + 2 < s_.size() && is_hex(s_[pos_ + 1]) && is_hex(s_[pos_ + 2])) {
                unsigned v = 0;
                std::from_chars(s_.data() + pos_ + 1, s_.data() + pos_ + 3, v, 16);
                value += static_cast<char>(v);
                pos_ += 3;
                continue;
            }
            value += c;
            ++pos_;
        }
        if (value.size() > max_string_length)
            report(Rule::string_length, line_,
                   "string of " + std::to_string(value.size()) + " characters; at most " +
                       std::to_string(max_string_length));
        push(TokenKind::string, std::move(value), line_);
    }

    void punct() {
        static constexpr std::string_view pairs[] = {":=", "<>", "<=", ">="};
        for (std::string_view p : pairs) {
            if (s_.substr(pos_, 2) == p) {
                push(TokenKind::punct, std::string(p), line_);
                pos_ += 2;
                return;
            }
        }
        const char c = s_[pos_];
        if (std::string_view(",;()[]{}.\\%+-*/=<>:?|").find(c) != std::string_view::npos) {
            push(TokenKind::punct, std::string(1, c), line_);
        } else {
            report(Rule::syntax, line_, std::string("unexpected character '") + c + "'");
            push(TokenKind::invalid, std::string(1, c), line_);
        }
        ++pos_;
    }

    std::string_view s_;
    std::string_view file_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    LexResult out_;
};

}  // namespace

LexResult lex(std::string_view text, std::string_view file) {
    return Lexer(text, file).run();
}

bool is_keyword(const Token& token, std::string_view word) {
    return token.kind == TokenKind::identifier && token.keyword && same_name(token.text, word);
}

bool is_punct(const Token& token, std::string_view p) {
    return token.kind == TokenKind::punct && token.text == p;
}

}  // namespace fibrecell::drivers::abb::rapid
