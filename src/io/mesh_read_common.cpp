#include "io/mesh_read_common.h"

#include "core/errors.h"

#include <charconv>
#include <system_error>

namespace xparam::detail {

void throw_input_error(const std::string& source, const std::string& what) {
  throw InputError(source + ": " + what);
}

namespace {
std::string_view without_plus(std::string_view token) {
  // from_chars refuses a leading '+', which some exporters write; "+-1" stays refused below.
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  return token;
}
}  // namespace

bool parse_double(std::string_view token, double& value) {
  token = without_plus(token);
  const char* end = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  return !token.empty() && error == std::errc() && stop == end;
}

bool parse_int(std::string_view token, std::int64_t& value) {
  token = without_plus(token);
  const char* end = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  return !token.empty() && error == std::errc() && stop == end;
}

TextCursor::TextCursor(std::string_view text, char comment, int first_line)
    : text_(text), comment_(comment), line_(first_line), token_line_(first_line) {}

void TextCursor::skip_blanks_and_comment() {
  while (position_ < text_.size()) {
    const char c = text_[position_];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++position_;
    } else if (comment_ != '\0' && c == comment_) {
      while (position_ < text_.size() && text_[position_] != '\n') ++position_;
    } else {
      return;
    }
  }
}

std::string_view TextCursor::next_token() {
  for (;;) {
    skip_blanks_and_comment();
    if (position_ == text_.size()) return {};
    if (text_[position_] != '\n') break;
    ++position_;
    ++line_;
  }
  return next_token_on_line();
}

std::string_view TextCursor::next_token_on_line() {
  skip_blanks_and_comment();
  token_line_ = line_;
  const std::size_t begin = position_;
  while (position_ < text_.size()) {
    const char c = text_[position_];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') break;
    if (comment_ != '\0' && c == comment_) break;
    ++position_;
  }
  return text_.substr(begin, position_ - begin);
}

void TextCursor::skip_line() {
  while (position_ < text_.size() && text_[position_] != '\n') ++position_;
  if (position_ < text_.size()) {
    ++position_;
    ++line_;
  }
}

std::string quote(std::string_view token) {
  constexpr std::size_t kLongest = 40;
  std::string shown(token.substr(0, kLongest));
  // Random bytes must not end up in a terminal as control characters.
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  }
  return "'" + shown + (token.size() > kLongest ? "...'" : "'");
}

}  // namespace xparam::detail
