#pragma once
// A cursor over a whole file held in memory: whitespace-separated tokens with line numbers, and
// raw byte blocks for binary sections. Shared by the mesh and stress readers; no iostreams, so a
// token costs a few comparisons and one from_chars.

#include "planner/input_error.hpp"

#include <cstddef>
#include <string>
#include <string_view>

namespace fibrecell::planner {

class TextScanner {
  public:
    // `text` must outlive the scanner; `file` names the file in error messages.
    TextScanner(std::string_view text, std::string file);

    const std::string& file() const { return file_; }
    // 1-based line of the last token or line read: the line errors point at.
    std::size_t line() const { return token_line_; }
    std::size_t remaining() const { return text_.size() - pos_; }

    // True when only whitespace is left.
    bool at_end();
    // True when nothing but blanks is left on the current line.
    bool at_line_end();

    // The next whitespace-separated token; `what` says what was expected, for the error at the
    // end of the file.
    std::string_view token(std::string_view what);
    // The next token without consuming it; empty at the end of the file.
    std::string_view peek() const;
    long long integer(std::string_view what);
    // An integer in [min, max]; the message names `what` and the range.
    long long integer(std::string_view what, long long min, long long max);
    // A finite floating-point number: "nan" and "inf" are rejected here, with the line.
    double real(std::string_view what);
    // A floating-point number that may be "nan" or "inf", for callers that report those later.
    double any_real(std::string_view what);
    // A double-quoted string on one line (Gmsh names); returns the text between the quotes.
    std::string_view quoted(std::string_view what);
    // Consumes the next token and requires it to equal `keyword` (case-insensitive).
    void expect(std::string_view keyword);
    void skip_tokens(long long count, std::string_view what);

    // Reads the rest of the current line (without CR/LF) and moves to the next one; false at the
    // end of the file.
    bool next_line(std::string_view& line);
    // Requires the current line to hold nothing more and moves past its newline: binary data in
    // legacy VTK starts right after the header line.
    void end_header_line();
    // The next `count` raw bytes; the error names `what` when the file is shorter.
    std::string_view bytes(std::size_t count, std::string_view what);

    // Rejects a negative count, or one the rest of the file cannot hold when each item takes at
    // least `min_bytes_each` bytes: guards allocations against absurd header counts.
    void check_count(long long count, std::size_t min_bytes_each, std::string_view what);

    InputError error(const std::string& problem) const;
    [[noreturn]] void fail(const std::string& problem) const;

  private:
    void skip_space();

    std::string_view text_;
    std::string file_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;        // line of pos_
    std::size_t token_line_ = 1;  // line of the last token
};

}  // namespace fibrecell::planner
