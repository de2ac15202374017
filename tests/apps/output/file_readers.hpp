#pragma once
// Independent readers of the files bemshape writes (VTK XML PolyData and ImageData, binary
// PLY), written from the format specifications for the tests: they check that a file is
// well-formed (balanced XML tags, declared sizes equal to the payload) and return its
// numbers so a test can compare them with what was written. What the programs users open
// the files with make of them is tested by output/test_vtk_readers.py (VTK's readers).

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace bemshape::testing {

/// Attributes name="value" of one XML start tag's text.
inline std::map<std::string, std::string> xml_attributes(const std::string& tag) {
  std::map<std::string, std::string> result;
  std::size_t pos = 0;
  while ((pos = tag.find("=\"", pos)) != std::string::npos) {
    std::size_t name_start = tag.rfind(' ', pos);
    const std::string name = tag.substr(name_start + 1, pos - name_start - 1);
    const std::size_t end = tag.find('"', pos + 2);
    result[name] = tag.substr(pos + 2, end - pos - 2);
    pos = end + 1;
  }
  return result;
}

/// One element of the XML tree with its text content (not nested elements' text).
struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<XmlElement> children;
  const XmlElement& child(const std::string& n) const {
    for (const XmlElement& c : children)
      if (c.name == n)
        return c;
    FAIL("no element <" << n << "> in <" << name << ">");
    return *this;
  }
};

/// Parses XML text into a tree, REQUIRE-ing that every start tag is closed by its own end tag
/// in the right order. The raw appended block of VTK files (after "_" up to
/// "</AppendedData>") is kept as the AppendedData element's text, byte for byte.
inline XmlElement parse_xml(const std::string& xml) {
  XmlElement root;
  std::vector<XmlElement*> stack{&root};
  std::size_t pos = 0;
  while (pos < xml.size()) {
    const std::size_t open = xml.find('<', pos);
    if (open == std::string::npos) {
      stack.back()->text += xml.substr(pos);
      break;
    }
    stack.back()->text += xml.substr(pos, open - pos);
    const std::size_t close = xml.find('>', open);
    REQUIRE(close != std::string::npos);
    const std::string tag = xml.substr(open + 1, close - open - 1);
    pos = close + 1;
    if (tag.starts_with("?"))
      continue;
    if (tag.starts_with("/")) {
      REQUIRE(stack.size() > 1);
      CHECK(tag.substr(1) == stack.back()->name);
      stack.pop_back();
      continue;
    }
    const bool self_closing = tag.ends_with("/");
    XmlElement element;
    element.name = tag.substr(0, tag.find_first_of(" /"));
    element.attributes = xml_attributes(tag);
    stack.back()->children.push_back(element);
    if (!self_closing)
      stack.push_back(&stack.back()->children.back());
    if (element.name == "AppendedData") {
      const std::size_t end = xml.rfind("</AppendedData>");
      REQUIRE(end != std::string::npos);
      stack.back()->text = xml.substr(pos, end - pos);
      pos = end;
    }
  }
  CHECK(stack.size() == 1);  // every element closed
  REQUIRE(root.children.size() == 1);
  return root.children.front();
}

/// The numbers of an ASCII DataArray as #tuples×components. Int64 arrays must hold integers
/// ("100000", never "1e+05").
inline Eigen::MatrixXd ascii_array(const XmlElement& array) {
  const int components = std::stoi(array.attributes.at("NumberOfComponents"));
  CHECK(array.attributes.at("format") == "ascii");
  const bool integer = array.attributes.at("type") == "Int64";
  std::istringstream in(array.text);
  std::vector<double> values;
  std::string token;
  while (in >> token) {
    if (integer)
      REQUIRE(token.find_first_not_of("-0123456789") == std::string::npos);
    values.push_back(std::stod(token));
  }
  REQUIRE(values.size() % components == 0);
  Eigen::MatrixXd m(static_cast<Eigen::Index>(values.size()) / components, components);
  for (Eigen::Index i = 0; i < m.size(); ++i)
    m(i / components, i % components) = values[static_cast<std::size_t>(i)];
  return m;
}

/// The start of the raw appended block of a VTK XML file (the byte after "_").
inline std::size_t appended_start(const XmlElement& file) {
  const XmlElement& data = file.child("AppendedData");
  CHECK(data.attributes.at("encoding") == "raw");
  const std::size_t underscore = data.text.find('_');
  REQUIRE(underscore != std::string::npos);
  return underscore + 1;
}

/// The numbers of a DataArray in the raw appended block (UInt64 byte-count header), Int64 or
/// Float64 or Float32, as #tuples×components doubles; REQUIREs that the block holds exactly
/// `tuples` tuples. `end` grows to the end of the array's block.
inline Eigen::MatrixXd appended_array(const XmlElement& array, const XmlElement& file,
                                      Eigen::Index tuples, std::size_t& end) {
  CHECK(array.attributes.at("format") == "appended");
  const int components = std::stoi(array.attributes.at("NumberOfComponents"));
  const std::string& type = array.attributes.at("type");
  REQUIRE((type == "Int64" || type == "Float64" || type == "Float32"));
  const std::size_t size = type == "Float32" ? 4 : 8;
  const std::string& raw = file.child("AppendedData").text;
  const std::size_t at = appended_start(file) + std::stoull(array.attributes.at("offset"));
  REQUIRE(at + 8 <= raw.size());
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, raw.data() + at, 8);
  REQUIRE(bytes == static_cast<std::uint64_t>(tuples) * components * size);
  REQUIRE(at + 8 + bytes <= raw.size());
  Eigen::MatrixXd m(tuples, components);
  const char* p = raw.data() + at + 8;
  for (Eigen::Index i = 0; i < m.size(); ++i, p += size) {
    double x = 0.0;
    if (type == "Int64") {
      std::int64_t v = 0;
      std::memcpy(&v, p, 8);
      x = static_cast<double>(v);
    } else if (type == "Float64") {
      std::memcpy(&x, p, 8);
    } else {
      float v = 0.0f;
      std::memcpy(&v, p, 4);
      x = v;
    }
    m(i / components, i % components) = x;
  }
  end = std::max(end, at + 8 + static_cast<std::size_t>(bytes));
  return m;
}

/// A DataArray in either form, checked to hold `tuples` tuples.
inline Eigen::MatrixXd data_array(const XmlElement& array, const XmlElement& file,
                                  Eigen::Index tuples, std::size_t& end) {
  if (array.attributes.at("format") == "ascii") {
    Eigen::MatrixXd m = ascii_array(array);
    CHECK(m.rows() == tuples);
    return m;
  }
  return appended_array(array, file, tuples, end);
}

struct VtpFile {
  Eigen::Index points = 0, polys = 0;
  Eigen::MatrixXd coordinates;  // #points×3
  Eigen::MatrixXd connectivity, offsets;
  std::map<std::string, Eigen::MatrixXd> point_data, cell_data;
};

/// Reads a .vtp with ASCII or raw appended arrays, checking that every array has as many
/// tuples as its location declares, that the offsets describe triangles and that the
/// appended blocks end where the data ends.
inline VtpFile parse_vtp(const std::string& text) {
  const XmlElement file = parse_xml(text);
  CHECK(file.name == "VTKFile");
  CHECK(file.attributes.at("type") == "PolyData");
  CHECK(file.attributes.at("byte_order") == "LittleEndian");
  CHECK(file.attributes.at("header_type") == "UInt64");
  const XmlElement& piece = file.child("PolyData").child("Piece");
  VtpFile vtp;
  vtp.points = std::stol(piece.attributes.at("NumberOfPoints"));
  vtp.polys = std::stol(piece.attributes.at("NumberOfPolys"));
  std::size_t end = 0;
  const XmlElement& points = piece.child("Points").child("DataArray");
  CHECK(points.attributes.at("type") == "Float64");
  CHECK(points.attributes.at("NumberOfComponents") == "3");
  vtp.coordinates = data_array(points, file, vtp.points, end);
  for (const XmlElement& a : piece.child("Polys").children) {
    CHECK(a.attributes.at("type") == "Int64");
    CHECK(a.attributes.at("NumberOfComponents") == "1");  // VTK refuses tuples here
    if (a.attributes.at("Name") == "connectivity")
      vtp.connectivity = data_array(a, file, 3 * vtp.polys, end);
    if (a.attributes.at("Name") == "offsets")
      vtp.offsets = data_array(a, file, vtp.polys, end);
  }
  REQUIRE(vtp.connectivity.size() == 3 * vtp.polys);
  REQUIRE(vtp.offsets.size() == vtp.polys);
  const Eigen::MatrixXd corners = vtp.connectivity;  // #polys×3: the corners of a face together
  vtp.connectivity = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      corners.data(), vtp.polys, 3);
  for (Eigen::Index f = 0; f < vtp.polys; ++f)
    CHECK(vtp.offsets(f) == 3.0 * double(f + 1));
  CHECK((vtp.connectivity.array() >= 0).all());
  CHECK((vtp.connectivity.array() < double(vtp.points)).all());
  for (const XmlElement& a : piece.child("PointData").children) {
    CHECK(a.attributes.at("type") == "Float64");
    vtp.point_data[a.attributes.at("Name")] = data_array(a, file, vtp.points, end);
  }
  for (const XmlElement& a : piece.child("CellData").children) {
    CHECK(a.attributes.at("type") == "Float64");
    vtp.cell_data[a.attributes.at("Name")] = data_array(a, file, vtp.polys, end);
  }
  if (end > 0) {  // only the closing newline and indentation may follow the last block
    const std::string& raw = file.child("AppendedData").text;
    CHECK(raw.substr(end).find_first_not_of(" \n") == std::string::npos);
  }
  return vtp;
}

struct VtiFile {
  std::array<long long, 6> extent{};
  Eigen::Vector3d origin, spacing;
  std::map<std::string, Eigen::MatrixXf> point_data, cell_data;
};

/// Reads a .vti with raw appended Float32 arrays (UInt64 block headers), checking each
/// block's byte count against the extent and that the blocks end where the data ends.
inline VtiFile parse_vti(const std::string& bytes) {
  const XmlElement file = parse_xml(bytes);
  CHECK(file.name == "VTKFile");
  CHECK(file.attributes.at("type") == "ImageData");
  CHECK(file.attributes.at("header_type") == "UInt64");
  const XmlElement& image = file.child("ImageData");
  VtiFile vti;
  std::istringstream extent(image.attributes.at("WholeExtent")),
      origin(image.attributes.at("Origin")), spacing(image.attributes.at("Spacing"));
  for (auto& e : vti.extent)
    extent >> e;
  origin >> vti.origin.x() >> vti.origin.y() >> vti.origin.z();
  spacing >> vti.spacing.x() >> vti.spacing.y() >> vti.spacing.z();
  long long points = 1, cells = 1;
  for (int d = 0; d < 3; ++d) {
    const long long n = vti.extent[2 * d + 1] - vti.extent[2 * d];
    points *= n + 1;
    cells *= std::max(n, 1LL);
  }
  std::size_t end = 0;
  const XmlElement& piece = image.child("Piece");
  for (const char* location : {"PointData", "CellData"}) {
    const long long tuples = std::string(location) == "PointData" ? points : cells;
    for (const XmlElement& a : piece.child(location).children) {
      CHECK(a.attributes.at("type") == "Float32");
      (std::string(location) == "PointData" ? vti.point_data
                                            : vti.cell_data)[a.attributes.at("Name")] =
          appended_array(a, file, tuples, end).cast<float>();
    }
  }
  // Only the closing newline and indentation may follow the last block.
  const std::string& raw = file.child("AppendedData").text;
  CHECK(raw.substr(std::max(end, appended_start(file))).find_first_not_of(" \n") ==
        std::string::npos);
  return vti;
}

struct PlyFile {
  std::vector<std::string> header;
  Eigen::MatrixXf vertices;  // #V×3
  Eigen::VectorXf field;     // #V
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3> colours;
  Eigen::MatrixX3i faces;
};

/// Reads the binary PLY layout of apps/output/ply_writer.hpp, checking the header's element
/// and property lines and that the payload is exactly #V·23 + #F·13 bytes.
inline PlyFile parse_ply(const std::string& bytes, const std::string& field_name) {
  const std::size_t end = bytes.find("end_header\n");
  REQUIRE(end != std::string::npos);
  PlyFile ply;
  std::istringstream header(bytes.substr(0, end));
  std::string line;
  long long nv = -1, nf = -1;
  while (std::getline(header, line)) {
    if (!line.starts_with("comment"))
      ply.header.push_back(line);
    if (line.starts_with("element vertex "))
      nv = std::stoll(line.substr(15));
    if (line.starts_with("element face "))
      nf = std::stoll(line.substr(13));
  }
  const std::vector<std::string> expected{"ply",
                                          "format binary_little_endian 1.0",
                                          "element vertex " + std::to_string(nv),
                                          "property float x",
                                          "property float y",
                                          "property float z",
                                          "property float " + field_name,
                                          "property float quality",
                                          "property uchar red",
                                          "property uchar green",
                                          "property uchar blue",
                                          "element face " + std::to_string(nf),
                                          "property list uchar int vertex_indices"};
  CHECK(ply.header == expected);
  const std::size_t start = end + 11;
  REQUIRE(bytes.size() - start == static_cast<std::size_t>(nv * 23 + nf * 13));
  ply.vertices.resize(nv, 3);
  ply.field.resize(nv);
  ply.colours.resize(nv, 3);
  ply.faces.resize(nf, 3);
  const char* p = bytes.data() + start;
  for (long long v = 0; v < nv; ++v, p += 23) {
    float values[5];
    std::memcpy(values, p, 20);
    ply.vertices.row(v) << values[0], values[1], values[2];
    ply.field(v) = values[3];
    CHECK(values[4] == values[3]);  // quality: the field again
    for (int c = 0; c < 3; ++c)
      ply.colours(v, c) = static_cast<std::uint8_t>(p[20 + c]);
  }
  for (long long f = 0; f < nf; ++f, p += 13) {
    CHECK(static_cast<unsigned char>(p[0]) == 3);
    std::int32_t indices[3];
    std::memcpy(indices, p + 1, 12);
    ply.faces.row(f) << indices[0], indices[1], indices[2];
  }
  return ply;
}

}  // namespace bemshape::testing
