// ASCII OFF reader (geometry/detail/polygon_file_readers.hpp).
#include <cstdint>
#include <string>

#include "geometry/detail/polygon_file_readers.hpp"
#include "geometry/detail/text_scan.hpp"

namespace bemshape::geometry::detail {
namespace {

/// The keyword without its optional prefixes ST, C, N, in this order (Geomview's OFF spec);
/// "4" and "n" (4-D and n-D vertices) are left in place and refused by the caller.
std::string_view strip_off_prefixes(std::string_view keyword) {
  for (const std::string_view prefix : {"ST", "C", "N"})
    if (keyword.substr(0, prefix.size()) == prefix)
      keyword.remove_prefix(prefix.size());
  return keyword;
}

}  // namespace

PolygonSoup read_off(const std::filesystem::path& path, std::string_view text) {
  LineScanner scanner(text, '#');
  if (!scanner.next_nonempty())
    fail(path, "the file contains only white space and comments");
  const std::string_view keyword = scanner.tokens()[0];
  const std::string_view bare = strip_off_prefixes(keyword);
  if (bare == "4OFF" || bare == "nOFF" || bare == "4nOFF")
    fail_at_line(path, scanner.line_number(),
                 quoted(keyword) + ": OFF files with 4-D or n-D vertices are not supported");
  if (bare != "OFF")
    fail_at_line(path, scanner.line_number(),
                 "not an OFF file: it starts with " + quoted(keyword) +
                     ", expected OFF (or COFF, NOFF, STOFF, ...)");
  std::size_t first_count = 1;
  if (scanner.tokens().size() > 1 && scanner.tokens()[1] == "BINARY")
    fail_at_line(path, scanner.line_number(),
                 "binary OFF is not supported: export ASCII OFF, PLY or STL instead");

  // The counts NV NF [NE] follow the keyword on its line or on the next one.
  if (scanner.tokens().size() == 1) {
    if (!scanner.next_nonempty())
      fail(path, "the OFF header ends after the keyword: the vertex and face counts are missing");
    first_count = 0;
  }
  std::uint64_t nv = 0, nf = 0;
  const auto& header = scanner.tokens();
  if (header.size() < first_count + 2 || !parse_count(header[first_count], nv) ||
      !parse_count(header[first_count + 1], nf))
    fail_at_line(path, scanner.line_number(),
                 "OFF header: expected the vertex, face and edge counts (whole numbers)");
  const std::size_t header_line = scanner.line_number();
  const auto truncated = [&](const std::string& what) {
    fail(path, "the OFF header (line " + std::to_string(header_line) + ") announces " +
                   std::to_string(nv) + " vertices and " + std::to_string(nf) +
                   " faces but the file ends " + what + ": the file is truncated or corrupt");
  };

  // Vectors grow with the lines actually read, never to a header's count.
  PolygonSoup soup;
  for (std::uint64_t v = 0; v < nv; ++v) {
    if (!scanner.next_nonempty())
      truncated("after " + std::to_string(v) + " vertices");
    const auto& tokens = scanner.tokens();
    if (tokens.size() < 3)
      fail_at_line(path, scanner.line_number(),
                   "vertex " + std::to_string(v) + " needs 3 coordinates, found " +
                       std::to_string(tokens.size()));
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) {
      std::string why;
      if (!parse_coordinate(tokens[static_cast<std::size_t>(k)], p(k), why))
        fail_at_line(path, scanner.line_number(), "vertex " + std::to_string(v) + ": " + why);
    }
    soup.points.push_back(p);
  }
  for (std::uint64_t f = 0; f < nf; ++f) {
    if (!scanner.next_nonempty())
      truncated("after " + std::to_string(f) + " faces");
    const auto& tokens = scanner.tokens();
    const std::size_t line = scanner.line_number();
    std::uint64_t n = 0;
    if (!parse_count(tokens[0], n))
      fail_at_line(
          path, line,
          "face " + std::to_string(f) + ": " + quoted(tokens[0]) + " is not a number of corners");
    if (n > tokens.size() - 1)
      fail_at_line(path, line,
                   "face " + std::to_string(f) + " announces " + std::to_string(n) +
                       " corners but lists " + std::to_string(tokens.size() - 1) +
                       " numbers: the file is corrupt");
    // Numbers after the n indices are the face's colour, which is not needed.
    for (std::size_t k = 1; k <= n; ++k) {
      std::uint64_t index = 0;
      if (!parse_count(tokens[k], index) || index >= nv)
        fail_at_line(path, line,
                     "face " + std::to_string(f) + " refers to vertex " + quoted(tokens[k]) +
                         " but the file has " + std::to_string(nv) +
                         " vertices (numbered from 0): the file is corrupt");
      soup.corners.push_back(static_cast<std::size_t>(index));
    }
    soup.start.push_back(soup.corners.size());
  }
  return soup;
}

}  // namespace bemshape::geometry::detail
