#pragma once
// Line and number scanning for bemshape's own text mesh readers (ASCII STL checks, OBJ, OFF,
// the header and ASCII body of PLY). Numbers go through std::from_chars: locale-independent,
// no allocation, and a token must be a number as a whole ("1.0abc" is refused, not read as
// 1.0, which is what stream-based readers do).

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "core/errors.hpp"

namespace bemshape::geometry::detail {

/// Throws InputError "<path>: <what>".
[[noreturn]] inline void fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError(path.string() + ": " + what);
}

/// Throws InputError "<path>: line <line>: <what>" (lines counted from 1).
[[noreturn]] inline void fail_at_line(const std::filesystem::path& path, std::size_t line,
                                      const std::string& what) {
  fail(path, "line " + std::to_string(line) + ": " + what);
}

/// Walks a text one line at a time ('\n' ends a line; '\r' and other white space separate
/// tokens), splitting each line into whitespace-separated tokens. With a comment character,
/// everything from it to the end of the line is dropped first.
class LineScanner {
 public:
  explicit LineScanner(std::string_view text, char comment = '\0')
      : text_(text), comment_(comment) {}

  /// Moves to the next line; false at the end of the text.
  bool next() {
    if (pos_ >= text_.size())
      return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos)
      end = text_.size();
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_number_;
    if (comment_ != '\0')
      line = line.substr(0, line.find(comment_));
    tokens_.clear();
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_space(line[i]))
        ++i;
      std::size_t j = i;
      while (j < line.size() && !is_space(line[j]))
        ++j;
      if (j > i)
        tokens_.push_back(line.substr(i, j - i));
      i = j;
    }
    return true;
  }

  /// Moves to the next line that has at least one token; false at the end of the text.
  bool next_nonempty() {
    while (next())
      if (!tokens_.empty())
        return true;
    return false;
  }

  /// Tokens of the current line.
  const std::vector<std::string_view>& tokens() const { return tokens_; }
  /// Number of the current line, counting from 1.
  std::size_t line_number() const { return line_number_; }
  /// Byte offset just past the current line's '\n' (where the next line starts).
  std::size_t next_offset() const { return pos_ < text_.size() ? pos_ : text_.size(); }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
  }

  std::string_view text_;
  char comment_;
  std::size_t pos_ = 0;
  std::size_t line_number_ = 0;
  std::vector<std::string_view> tokens_;
};

/// `'<token>'` for a message, with bytes outside printable ASCII shown as \xNN and long
/// tokens cut, so that a binary file's garbage does not end up raw in a one-line message.
inline std::string quoted(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::ostringstream out;
  out << '\'';
  for (std::size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out << static_cast<char>(c);
    } else {
      static const char hex[] = "0123456789abcdef";
      out << "\\x" << hex[c >> 4] << hex[c & 15];
    }
  }
  if (token.size() > kMaxShown)
    out << "...";
  out << '\'';
  return out.str();
}

/// Parses a whole token as a finite double (a leading '+' is accepted); otherwise explains
/// what is wrong in `why`.
inline bool parse_coordinate(std::string_view token, double& value, std::string& why) {
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+')
    ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last) {
    why = quoted(token) + " is not a number";
    return false;
  }
  if (!std::isfinite(value)) {
    why = "coordinate " + quoted(token) + " is not finite";
    return false;
  }
  return true;
}

/// Parses a whole token as a signed integer (a leading '+' is accepted).
inline bool parse_integer(std::string_view token, std::int64_t& value) {
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+')
    ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last;
}

/// Parses a whole token as a count (a non-negative integer).
inline bool parse_count(std::string_view token, std::uint64_t& value) {
  const char* last = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), last, value);
  return ec == std::errc() && ptr == last;
}

}  // namespace bemshape::geometry::detail
