// Wavefront OBJ reader (geometry/detail/polygon_file_readers.hpp).
#include <cstdint>
#include <string>

#include "geometry/detail/polygon_file_readers.hpp"
#include "geometry/detail/text_scan.hpp"

namespace bemshape::geometry::detail {

PolygonSoup read_obj(const std::filesystem::path& path, std::string_view text) {
  PolygonSoup soup;
  // Positive indices may refer to vertices defined further down, so they are checked at the
  // end; the largest one and its line are kept for the message.
  std::size_t largest_index = 0, largest_line = 0;
  LineScanner scanner(text, '#');
  while (scanner.next_nonempty()) {
    const auto& tokens = scanner.tokens();
    const std::size_t line = scanner.line_number();
    if (tokens[0] == "v") {
      if (tokens.size() < 4)
        fail_at_line(path, line,
                     "a vertex needs 3 coordinates, found " + std::to_string(tokens.size() - 1));
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        std::string why;
        if (!parse_coordinate(tokens[static_cast<std::size_t>(k) + 1], p(k), why))
          fail_at_line(path, line, why);
      }
      soup.points.push_back(p);
    } else if (tokens[0] == "f") {
      if (tokens.size() < 2)
        fail_at_line(path, line, "a face line lists no vertices");
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        const std::string_view vertex = tokens[k].substr(0, tokens[k].find('/'));
        std::int64_t number = 0;
        if (!parse_integer(vertex, number) || number == 0)
          fail_at_line(path, line,
                       quoted(tokens[k]) +
                           " is not a face corner (a vertex number counting from 1, or negative "
                           "counting back from the last vertex, optionally followed by "
                           "/texture/normal numbers)");
        std::size_t index = 0;
        if (number < 0) {
          const auto back = static_cast<std::uint64_t>(-(number + 1)) + 1;  // no overflow
          if (back > soup.points.size())
            fail_at_line(path, line,
                         "a face refers to vertex " + std::to_string(number) + " but only " +
                             std::to_string(soup.points.size()) +
                             " vertices precede it: the file is corrupt");
          index = soup.points.size() - back;
        } else {
          index = static_cast<std::size_t>(number) - 1;
          if (index >= largest_index) {
            largest_index = index;
            largest_line = line;
          }
        }
        soup.corners.push_back(index);
      }
      soup.start.push_back(soup.corners.size());
    }
  }
  if (largest_line > 0 && largest_index >= soup.points.size())
    fail_at_line(path, largest_line,
                 "a face refers to vertex number " + std::to_string(largest_index + 1) +
                     " (counting from 1) but the file has only " +
                     std::to_string(soup.points.size()) + " vertices");
  return soup;
}

}  // namespace bemshape::geometry::detail
