#include "planner/io/text_scanner.hpp"

#include "planner/io/number_parse.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fibrecell::planner {
namespace {

inline bool is_space(char c) {
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

inline bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r';
}

}  // namespace

TextScanner::TextScanner(std::string_view text, std::string file)
    : text_(text), file_(std::move(file)) {
    if (text_.starts_with("\xEF\xBB\xBF")) pos_ = 3;  // UTF-8 byte-order mark from some editors
}

void TextScanner::skip_space() {
    const char* p = text_.data() + pos_;
    const char* const end = text_.data() + text_.size();
    std::size_t newlines = 0;
    while (p != end && is_space(*p)) {
        newlines += (*p == '\n');
        ++p;
    }
    line_ += newlines;
    pos_ = static_cast<std::size_t>(p - text_.data());
}

bool TextScanner::at_end() {
    skip_space();
    return pos_ == text_.size();
}

bool TextScanner::at_line_end() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) ++pos_;
    return pos_ == text_.size() || text_[pos_] == '\n';
}

std::string_view TextScanner::token(std::string_view what) {
    skip_space();
    token_line_ = line_;
    if (pos_ == text_.size()) fail("unexpected end of file: expected " + std::string(what));
    const std::size_t start = pos_;
    const char* p = text_.data() + pos_;
    const char* const end = text_.data() + text_.size();
    while (p != end && !is_space(*p)) ++p;
    pos_ = static_cast<std::size_t>(p - text_.data());
    return text_.substr(start, pos_ - start);
}

std::string_view TextScanner::peek() const {
    // Leaves the position alone: in binary VTK the bytes after a header are data, not text.
    std::size_t start = pos_;
    while (start < text_.size() && is_space(text_[start])) ++start;
    std::size_t end = start;
    while (end < text_.size() && !is_space(text_[end])) ++end;
    return text_.substr(start, end - start);
}

long long TextScanner::integer(std::string_view what) {
    const std::string_view tok = token(what);
    const auto value = parse_integer(tok);
    if (!value) fail("expected " + std::string(what) + " (an integer), found '" + shown(tok) + "'");
    return *value;
}

long long TextScanner::integer(std::string_view what, long long min, long long max) {
    const long long value = integer(what);
    if (value < min || value > max)
        fail(std::string(what) + " " + std::to_string(value) + " is outside " +
             std::to_string(min) + ".." + std::to_string(max));
    return value;
}

double TextScanner::real(std::string_view what) {
    const std::string_view tok = token(what);
    const auto value = parse_real(tok);
    if (!value) fail("expected " + std::string(what) + " (a number), found '" + shown(tok) + "'");
    if (!std::isfinite(*value))
        fail(std::string(what) + " is not a finite number: '" + shown(tok) + "'");
    return *value;
}

double TextScanner::any_real(std::string_view what) {
    const std::string_view tok = token(what);
    const auto value = parse_real(tok);
    if (!value) fail("expected " + std::string(what) + " (a number), found '" + shown(tok) + "'");
    return *value;
}

std::string_view TextScanner::quoted(std::string_view what) {
    skip_space();
    token_line_ = line_;
    if (pos_ == text_.size() || text_[pos_] != '"')
        fail("expected " + std::string(what) + " in double quotes, found '" + shown(peek()) + "'");
    const std::size_t start = pos_ + 1;
    std::size_t end = start;
    while (end < text_.size() && text_[end] != '"' && text_[end] != '\n') ++end;
    if (end == text_.size() || text_[end] != '"') fail("unterminated quoted " + std::string(what));
    pos_ = end + 1;
    return text_.substr(start, end - start);
}

void TextScanner::expect(std::string_view keyword) {
    const std::string_view tok = token(keyword);
    if (!iequals(tok, keyword))
        fail("expected '" + std::string(keyword) + "', found '" + shown(tok) + "'");
}

void TextScanner::skip_tokens(long long count, std::string_view what) {
    for (long long i = 0; i < count; ++i) token(what);
}

bool TextScanner::next_line(std::string_view& line) {
    if (pos_ == text_.size()) return false;
    token_line_ = line_;
    const std::size_t newline = text_.find('\n', pos_);
    const std::size_t end = newline == std::string_view::npos ? text_.size() : newline;
    line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (newline == std::string_view::npos) {
        pos_ = text_.size();
    } else {
        pos_ = newline + 1;
        ++line_;
    }
    return true;
}

void TextScanner::end_header_line() {
    if (!at_line_end()) fail("unexpected '" + shown(peek()) + "' at the end of the header line");
    if (pos_ < text_.size()) {
        ++pos_;
        ++line_;
    }
}

std::string_view TextScanner::bytes(std::size_t count, std::string_view what) {
    if (count > remaining())
        fail("file ends inside the binary " + std::string(what) + ": needs " +
             std::to_string(count) + " bytes, " + std::to_string(remaining()) + " left");
    const std::string_view block = text_.substr(pos_, count);
    // Keep line numbers meaningful for the text that follows the block.
    line_ += static_cast<std::size_t>(std::count(block.begin(), block.end(), '\n'));
    pos_ += count;
    return block;
}

void TextScanner::check_count(long long count, std::size_t min_bytes_each, std::string_view what) {
    if (count < 0) fail("negative " + std::string(what) + " count " + std::to_string(count));
    if (min_bytes_each == 0) min_bytes_each = 1;
    if (static_cast<unsigned long long>(count) > (remaining() + 1) / min_bytes_each)
        fail(std::string(what) + " count " + std::to_string(count) +
             " is more than the rest of the file can hold (" + std::to_string(remaining()) +
             " bytes)");
}

InputError TextScanner::error(const std::string& problem) const {
    return InputError::at_line(file_, token_line_, problem);
}

void TextScanner::fail(const std::string& problem) const {
    throw error(problem);
}

}  // namespace fibrecell::planner
