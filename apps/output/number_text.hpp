#pragma once
// Shortest decimal text of a double that reads back to the same double (std::to_chars), for
// the text writers: a value written to .csv or .vtp and parsed back is bit-identical.

#include <charconv>
#include <string>

namespace bemshape::output {

/// Appends the shortest round-trip decimal form of `x` to `text` ("0.3", "1e+06", "-2").
inline void append_number(std::string& text, double x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  text.append(buffer, result.ptr);
}

}  // namespace bemshape::output
