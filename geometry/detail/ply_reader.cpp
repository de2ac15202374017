// PLY reader, ASCII and binary (geometry/detail/polygon_file_readers.hpp).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

#include "core/number_text.hpp"
#include "geometry/detail/polygon_file_readers.hpp"
#include "geometry/detail/text_scan.hpp"

namespace bemshape::geometry::detail {
namespace {

namespace fs = std::filesystem;

enum class Format { ascii, binary_little_endian, binary_big_endian };

struct ScalarType {
  std::size_t bytes;
  bool is_integer;
  bool is_signed;
};

/// PLY's scalar types under both their old and their sized names.
std::optional<ScalarType> scalar_type(std::string_view name) {
  if (name == "char" || name == "int8")
    return ScalarType{1, true, true};
  if (name == "uchar" || name == "uint8")
    return ScalarType{1, true, false};
  if (name == "short" || name == "int16")
    return ScalarType{2, true, true};
  if (name == "ushort" || name == "uint16")
    return ScalarType{2, true, false};
  if (name == "int" || name == "int32")
    return ScalarType{4, true, true};
  if (name == "uint" || name == "uint32")
    return ScalarType{4, true, false};
  if (name == "float" || name == "float32")
    return ScalarType{4, false, true};
  if (name == "double" || name == "float64")
    return ScalarType{8, false, true};
  return std::nullopt;
}

struct Property {
  std::string name;
  bool is_list = false;
  ScalarType count_type{};  // lists only
  ScalarType value_type{};
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  std::size_t header_line = 0;
};

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // first byte after the end_header line
  std::size_t body_line = 0;    // its line number (ASCII)
};

Header read_header(const fs::path& path, std::string_view text) {
  LineScanner scanner(text);
  if (!scanner.next() || scanner.tokens().size() != 1 || scanner.tokens()[0] != "ply")
    fail(path, "not a PLY file: the first line is not 'ply'");
  Header header;
  bool saw_format = false;
  while (scanner.next()) {
    const auto& tokens = scanner.tokens();
    const std::size_t line = scanner.line_number();
    if (tokens.empty())
      continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "end_header") {
      if (!saw_format)
        fail_at_line(path, line, "the PLY header has no 'format' line");
      header.body_offset = scanner.next_offset();
      header.body_line = line + 1;
      return header;
    }
    if (keyword == "comment" || keyword == "obj_info")
      continue;
    if (keyword == "format") {
      if (tokens.size() != 3 || tokens[2] != "1.0")
        fail_at_line(path, line,
                     "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (tokens[1] == "ascii")
        header.format = Format::ascii;
      else if (tokens[1] == "binary_little_endian")
        header.format = Format::binary_little_endian;
      else if (tokens[1] == "binary_big_endian")
        header.format = Format::binary_big_endian;
      else
        fail_at_line(path, line, "unknown PLY format " + quoted(tokens[1]));
      saw_format = true;
    } else if (keyword == "element") {
      Element element;
      if (tokens.size() != 3 || !parse_count(tokens[2], element.count))
        fail_at_line(path, line, "expected 'element <name> <count>'");
      element.name = std::string(tokens[1]);
      element.header_line = line;
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty())
        fail_at_line(path, line, "a property before any 'element' line");
      Property property;
      std::optional<ScalarType> count_type, value_type;
      if (tokens.size() == 5 && tokens[1] == "list") {
        property.is_list = true;
        count_type = scalar_type(tokens[2]);
        value_type = scalar_type(tokens[3]);
        if (!count_type || !value_type || !count_type->is_integer)
          fail_at_line(path, line,
                       "expected 'property list <integer type> <type> <name>' with PLY types "
                       "(char, uchar, short, ushort, int, uint, float, double)");
        property.count_type = *count_type;
      } else {
        value_type = tokens.size() == 3 ? scalar_type(tokens[1]) : std::nullopt;
        if (!value_type)
          fail_at_line(path, line,
                       "expected 'property <type> <name>' with a PLY type (char, uchar, short, "
                       "ushort, int, uint, float, double)");
      }
      property.value_type = *value_type;
      property.name = std::string(tokens.back());
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail_at_line(path, line, "unknown PLY header line starting with " + quoted(keyword));
    }
  }
  fail(path, "the PLY header has no 'end_header' line: the file is truncated or corrupt");
}

/// Values of an ASCII body, one whitespace-separated token at a time across lines.
class AsciiValues {
 public:
  AsciiValues(const fs::path& path, std::string_view body, std::size_t first_line)
      : path_(path), scanner_(body), first_line_(first_line) {}

  /// The next value; false at the end of the data.
  bool next(const ScalarType& type, double& value) {
    while (index_ >= scanner_.tokens().size()) {
      if (!scanner_.next())
        return false;
      index_ = 0;
    }
    const std::string_view token = scanner_.tokens()[index_++];
    if (type.is_integer) {
      std::int64_t integer = 0;
      if (!parse_integer(token, integer))
        fail_at_line(path_, line(), quoted(token) + " is not an integer");
      value = static_cast<double>(integer);
      return true;
    }
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (first != last && *first == '+')
      ++first;
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || ptr != last)
      fail_at_line(path_, line(), quoted(token) + " is not a number");
    return true;
  }

  std::string where() const { return "line " + std::to_string(line()); }

 private:
  std::size_t line() const { return first_line_ + scanner_.line_number() - 1; }

  const fs::path& path_;
  LineScanner scanner_;
  std::size_t first_line_;
  std::size_t index_ = 0;
};

/// Values of a binary body, in the file's byte order.
class BinaryValues {
 public:
  BinaryValues(std::string_view body, std::size_t body_offset, bool big_endian)
      : body_(body),
        body_offset_(body_offset),
        swap_(big_endian != (std::endian::native == std::endian::big)) {}

  bool next(const ScalarType& type, double& value) {
    if (type.bytes > body_.size() - pos_)
      return false;
    std::array<unsigned char, 8> bytes{};
    std::memcpy(bytes.data(), body_.data() + pos_, type.bytes);
    pos_ += type.bytes;
    // Byte order: reverse the first type.bytes bytes. A loop rather than std::reverse, which
    // GCC 12 with -march=native reports as writing past the array (-Wstringop-overflow).
    if (swap_)
      for (std::size_t i = 0, j = type.bytes; i + 1 < j; ++i, --j) std::swap(bytes[i], bytes[j - 1]);
    value = decode(type, bytes.data());
    return true;
  }

  std::string where() const { return "byte " + std::to_string(body_offset_ + pos_); }

 private:
  static double decode(const ScalarType& type, const unsigned char* b) {
    if (!type.is_integer) {
      if (type.bytes == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    switch (type.bytes) {
      case 1: {
        std::uint8_t u;
        std::memcpy(&u, b, 1);
        return type.is_signed ? static_cast<double>(static_cast<std::int8_t>(u)) : u;
      }
      case 2: {
        std::uint16_t u;
        std::memcpy(&u, b, 2);
        return type.is_signed ? static_cast<double>(static_cast<std::int16_t>(u)) : u;
      }
      default: {
        std::uint32_t u;
        std::memcpy(&u, b, 4);
        return type.is_signed ? static_cast<double>(static_cast<std::int32_t>(u)) : u;
      }
    }
  }

  std::string_view body_;
  std::size_t body_offset_;
  bool swap_;
  std::size_t pos_ = 0;
};

/// The fewest bytes one item of `element` can take in the body: a binary scalar its size, an
/// ASCII value one character and a separator; a list at least its count.
std::uint64_t min_item_bytes(const Element& element, Format format) {
  std::uint64_t bytes = 0;
  for (const Property& p : element.properties)
    bytes += format == Format::ascii ? 2 : (p.is_list ? p.count_type.bytes : p.value_type.bytes);
  return bytes;
}

/// Where the reader finds the mesh in the header's elements.
struct Layout {
  std::size_t vertex_element = 0;
  std::array<std::size_t, 3> xyz{};  // property indices of x, y, z
  std::optional<std::size_t> face_element;
  std::size_t face_indices = 0;  // property index of vertex_indices
};

Layout find_layout(const fs::path& path, const Header& header) {
  Layout layout;
  bool saw_vertex = false;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    const auto property =
        [&](std::initializer_list<std::string_view> names) -> std::optional<std::size_t> {
      for (std::size_t p = 0; p < element.properties.size(); ++p)
        for (const std::string_view name : names)
          if (element.properties[p].name == name)
            return p;
      return std::nullopt;
    };
    if (element.name == "vertex") {
      if (saw_vertex)
        fail_at_line(path, element.header_line, "a second 'vertex' element in the PLY header");
      saw_vertex = true;
      layout.vertex_element = e;
      const char* names[] = {"x", "y", "z"};
      for (std::size_t k = 0; k < 3; ++k) {
        const auto p = property({names[k]});
        if (!p || element.properties[*p].is_list)
          fail_at_line(path, element.header_line,
                       std::string("the vertex element has no scalar property '") + names[k] + "'");
        layout.xyz[k] = *p;
      }
    } else if (element.name == "face") {
      if (layout.face_element)
        fail_at_line(path, element.header_line, "a second 'face' element in the PLY header");
      const auto p = property({"vertex_indices", "vertex_index"});
      if (!p || !element.properties[*p].is_list || !element.properties[*p].value_type.is_integer)
        fail_at_line(path, element.header_line,
                     "the face element has no integer list property 'vertex_indices'");
      layout.face_element = e;
      layout.face_indices = *p;
    }
  }
  if (!saw_vertex)
    fail(path, "the PLY header declares no 'vertex' element");
  if (!layout.face_element)
    fail(path,
         "the PLY header declares no 'face' element: bemshape needs a surface mesh of triangles "
         "or polygons, not a point cloud");
  return layout;
}

template <class Values>
PolygonSoup read_body(const fs::path& path, const Header& header, const Layout& layout,
                      Values& values) {
  PolygonSoup soup;
  std::uint64_t num_vertices = 0;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    if (element.properties.empty())
      continue;  // no data, whatever its count
    const bool is_vertex = e == layout.vertex_element;
    const bool is_face = layout.face_element && e == *layout.face_element;
    if (is_vertex)
      num_vertices = element.count;
    // Vectors grow with the items actually read, never to a header's count.
    for (std::uint64_t item = 0; item < element.count; ++item) {
      Eigen::Vector3d point = Eigen::Vector3d::Zero();
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const auto read = [&](const ScalarType& type, double& value) {
          if (!values.next(type, value))
            fail(path, "the PLY header announces " + std::to_string(element.count) + " " +
                           element.name + " elements but the data ends in number " +
                           std::to_string(item) + " (" + values.where() +
                           "): the file is truncated or corrupt");
        };
        double value = 0.0;
        if (!property.is_list) {
          read(property.value_type, value);
          if (is_vertex) {
            for (std::size_t k = 0; k < 3; ++k) {
              if (layout.xyz[k] != p)
                continue;
              if (!std::isfinite(value))
                fail(path, "vertex " + std::to_string(item) + " has a non-finite coordinate (" +
                               values.where() + "): the file is corrupt");
              point(static_cast<Eigen::Index>(k)) = value;
            }
          }
          continue;
        }
        double count = 0.0;
        read(property.count_type, count);
        if (count < 0)
          fail(path, element.name + " " + std::to_string(item) + ": negative list length (" +
                         values.where() + "): the file is corrupt");
        const bool indices = is_face && p == layout.face_indices;
        for (double k = 0; k < count; ++k) {
          read(property.value_type, value);
          if (!indices)
            continue;
          // value is an integer (integer type); num_vertices is final: vertices come first
          // in every file we know, and a face before its vertices is refused here.
          if (value < 0 || value >= static_cast<double>(num_vertices))
            fail(path, "face " + std::to_string(item) + " refers to vertex " +
                           // 20 digits: any 64-bit index in full, never through int64,
                           // which a 64-bit unsigned index can exceed (UBSan).
                           number_text(value, 20) + " but the file has " +
                           std::to_string(num_vertices) + " vertices before it (" + values.where() +
                           "): the file is corrupt");
          soup.corners.push_back(static_cast<std::size_t>(value));
        }
      }
      if (is_vertex)
        soup.points.push_back(point);
      if (is_face)
        soup.start.push_back(soup.corners.size());
    }
  }
  return soup;
}

}  // namespace

PolygonSoup read_ply(const fs::path& path, std::string_view text) {
  const Header header = read_header(path, text);
  const Layout layout = find_layout(path, header);
  const std::string_view body = text.substr(header.body_offset);

  // A header whose counts need more bytes than the file has is refused before reading.
  double needed = 0.0;  // double: counts up to 2^64 times item sizes cannot overflow
  for (const Element& element : header.elements)
    needed += static_cast<double>(element.count) *
              static_cast<double>(min_item_bytes(element, header.format));
  if (needed > static_cast<double>(body.size()) + 1.0)
    fail(path, "the PLY header announces elements that need at least " +
                   std::to_string(static_cast<std::uint64_t>(std::min(needed, 1e19))) +
                   " bytes but only " + std::to_string(body.size()) +
                   " follow it: the file is truncated or the header is corrupt");

  if (header.format == Format::ascii) {
    AsciiValues values(path, body, header.body_line);
    return read_body(path, header, layout, values);
  }
  BinaryValues values(body, header.body_offset, header.format == Format::binary_big_endian);
  return read_body(path, header, layout, values);
}

}  // namespace bemshape::geometry::detail
