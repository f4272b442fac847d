#pragma once
/// \file
/// Pieces shared by the mesh-format parsers behind read_triangle_soup (io/mesh_reader.h):
/// the error every parser throws, strict number parsing, and a cursor over text that keeps
/// line numbers for the messages. Internal to src/io.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace xparam::detail {

/// Throws InputError("<source>: <what>").
[[noreturn]] void throw_input_error(const std::string& source, const std::string& what);

/// Parses the whole of `token` as a decimal floating-point number ("nan" and "inf" included,
/// a leading '+' accepted). Returns false when any character is left over or nothing parses.
bool parse_double(std::string_view token, double& value);

/// Parses the whole of `token` as a decimal integer (a leading '+' accepted). Returns false on
/// trailing characters or when the value does not fit in 64 bits.
bool parse_int(std::string_view token, std::int64_t& value);

/// Reads whitespace-separated tokens from text, counting lines (1-based) for messages.
/// `comment` starts a comment that runs to the end of its line ('\0' for formats without).
class TextCursor {
 public:
  TextCursor(std::string_view text, char comment, int first_line = 1);

  /// The next token, or an empty view at the end of the text. Skips comments and newlines.
  std::string_view next_token();

  /// The next token on the current line, or an empty view when the line (or text) ends first.
  std::string_view next_token_on_line();

  /// Skips what is left of the current line, including its newline.
  void skip_line();

  /// The line of the token returned last (or of the cursor before any token).
  int line() const { return token_line_; }

  /// Bytes not consumed yet (an upper bound on what the rest of the file can hold).
  std::size_t remaining() const { return text_.size() - position_; }

 private:
  void skip_blanks_and_comment();

  std::string_view text_;
  char comment_;
  std::size_t position_ = 0;
  int line_;
  int token_line_;
};

/// `token` quoted for a message, shortened to at most 40 characters.
std::string quote(std::string_view token);

}  // namespace xparam::detail
