#pragma once
// RAPID text to tokens. Checks the byte-level rules on the way (ASCII only, no BOM, LF or CRLF
// line ends, identifiers <= 32 characters, strings <= 80) and reports them without stopping, so
// one pass finds every lexical problem; bytes it cannot use are skipped after being reported.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rapid/diagnostic.hpp"

namespace fibrecell::drivers::abb::rapid {

enum class TokenKind {
    identifier,  // names and reserved words; `keyword` tells them apart
    number,
    string,   // text holds the value with "" and \\ unescaped
    punct,    // := <> <= >= , ; ( ) [ ] { } . \ % + - * / = < > : ? |
    invalid,  // something the lexer already reported as a syntax error
    end,
};

struct Token {
    TokenKind kind = TokenKind::end;
    std::string text;      // as written for names and numbers; the value for strings
    bool keyword = false;  // a reserved word (any case)
    double number = 0;
    std::size_t line = 0;
};

struct LexResult {
    std::vector<Token> tokens;        // always ends with an `end` token
    std::vector<std::string> header;  // the %%% block's lines, trimmed
    std::size_t line_count = 0;
    std::vector<Diagnostic> diagnostics;
};

// `file` only labels the diagnostics.
LexResult lex(std::string_view text, std::string_view file);

// Whether `token` is the reserved word `word` (given in upper case).
bool is_keyword(const Token& token, std::string_view word);
bool is_punct(const Token& token, std::string_view p);

}  // namespace fibrecell::drivers::abb::rapid
