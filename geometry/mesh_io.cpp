#include "geometry/mesh_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <OpenMesh/Core/IO/IOInstances.hh>
#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>
#include <vector>

#include "core/errors.hpp"
#include "geometry/detail/3mf_reader.hpp"
#include "geometry/detail/polygon_file_readers.hpp"
#include "geometry/detail/text_scan.hpp"

namespace bemshape::geometry {
namespace {

namespace fs = std::filesystem;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

// A binary STL is an 80-byte header, a uint32 triangle count and 50 bytes per triangle.
constexpr std::uint64_t kStlHeaderBytes = 84;
constexpr std::uint64_t kStlTriangleBytes = 50;

using detail::fail;

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// Collects the vertices and triangles of OpenMesh's STL reader without building any
/// connectivity, so that non-manifold and inconsistently oriented faces survive to be
/// reported.
class SoupImporter final : public OpenMesh::IO::BaseImporter {
 public:
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  std::size_t short_faces = 0;
  // First face corner that refers to a vertex the file does not have (-1: none).
  long long bad_index = -1;

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override {
    return push(Eigen::Vector3d(p[0], p[1], p[2]));
  }
  VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
    return push(Eigen::Vector3d(p[0], p[1], p[2]));
  }
  VertexHandle add_vertex() override { return push(Eigen::Vector3d::Zero()); }
  void set_point(VertexHandle vh, const OpenMesh::Vec3f& p) override {
    if (vh.is_valid() && static_cast<std::size_t>(vh.idx()) < points.size())
      points[static_cast<std::size_t>(vh.idx())] = Eigen::Vector3d(p[0], p[1], p[2]);
  }

  FaceHandle add_face(const VHandles& corners) override {
    for (const VertexHandle& vh : corners) {
      if (!vh.is_valid() || static_cast<std::size_t>(vh.idx()) >= points.size()) {
        if (bad_index < 0)
          bad_index = vh.idx();
        return FaceHandle();
      }
    }
    if (corners.size() < 3) {
      ++short_faces;
      return FaceHandle();
    }
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      triangles.push_back({corners[0].idx(), corners[k].idx(), corners[k + 1].idx()});
    return FaceHandle(static_cast<int>(triangles.size()) - 1);
  }

  // Everything below is attribute or connectivity data a triangle soup does not keep.
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(OpenMesh::EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

  size_t n_vertices() const override { return points.size(); }
  size_t n_faces() const override { return triangles.size(); }
  size_t n_edges() const override { return 0; }

 private:
  VertexHandle push(const Eigen::Vector3d& p) {
    points.push_back(p);
    return VertexHandle(static_cast<int>(points.size()) - 1);
  }
};

/// Silences OpenMesh's own error and log streams while a file is read: library code never
/// prints, and every failure is reported through InputError instead.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : err_(omerr().is_enabled()), log_(omlog().is_enabled()) {
    omerr().disable();
    omlog().disable();
  }
  ~QuietOpenMesh() {
    if (err_)
      omerr().enable();
    if (log_)
      omlog().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  bool err_, log_;
};

/// "a FIFO (named pipe)", "a socket", ... for the refusal of a non-regular input.
std::string file_kind(mode_t mode) {
  if (S_ISDIR(mode))
    return "a directory";
  if (S_ISFIFO(mode))
    return "a FIFO (named pipe)";
  if (S_ISSOCK(mode))
    return "a socket";
  if (S_ISCHR(mode))
    return "a character device";
  if (S_ISBLK(mode))
    return "a block device";
  return "not a regular file";
}

[[noreturn]] void refuse_non_regular(const fs::path& path, mode_t mode) {
  fail(path, "is " + file_kind(mode) + ", not a regular mesh file; give the path of the file itself");
}

/// The whole file. It is opened with O_NONBLOCK and its type checked on the descriptor
/// before any read: opening a FIFO without it would block until a writer appears, and the
/// check on the open descriptor (not only on the path beforehand) also holds if the path is
/// replaced between the two.
std::string read_all(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    fail(path, std::string("cannot be opened for reading: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0)
    fail(path, std::string("cannot be examined: ") + std::strerror(errno));
  if (!S_ISREG(info.st_mode))
    refuse_non_regular(path, info.st_mode);
  std::string text;
  text.reserve(static_cast<std::size_t>(std::max<off_t>(info.st_size, 0)));
  std::array<char, 1 << 16> buffer{};
  while (true) {
    const ssize_t n = ::read(fd, buffer.data(), buffer.size());
    if (n == 0)
      break;
    if (n < 0) {
      if (errno == EINTR)
        continue;
      fail(path, std::string("read error: ") + std::strerror(errno));
    }
    text.append(buffer.data(), static_cast<std::size_t>(n));
  }
  return text;
}

/// Checks every `vertex x y z` line of an ASCII STL and that each facet has three of them;
/// returns the number of facets.
std::size_t lint_ascii_stl(const fs::path& path, std::string_view text) {
  std::size_t facets = 0, vertices = 0;
  bool saw_end = false;
  detail::LineScanner scanner(text);
  while (scanner.next_nonempty()) {
    const auto& tokens = scanner.tokens();
    const std::string keyword = lowercase(std::string(tokens[0]));
    if (keyword == "facet")
      ++facets;
    if (keyword == "endsolid")
      saw_end = true;
    if (keyword != "vertex")
      continue;
    ++vertices;
    if (tokens.size() != 4)
      detail::fail_at_line(
          path, scanner.line_number(),
          "a vertex needs 3 coordinates, found " + std::to_string(tokens.size() - 1));
    for (std::size_t k = 1; k <= 3; ++k) {
      double value;
      std::string why;
      if (!detail::parse_coordinate(tokens[k], value, why))
        detail::fail_at_line(path, scanner.line_number(), why);
    }
  }
  if (facets == 0)
    fail(path, "ASCII STL contains no facets");
  if (!saw_end)
    fail(path, "ASCII STL ends without 'endsolid': the file is truncated");
  if (vertices != 3 * facets)
    fail(path, "ASCII STL has " + std::to_string(facets) + " facets but " +
                   std::to_string(vertices) +
                   " vertex lines (3 per facet expected): the file is truncated or corrupt");
  return facets;
}

/// Decides binary vs ASCII STL the way OpenMesh does (a binary file's size is exactly
/// 84 + 50·n), but refuses a size mismatch up front instead of reading n triangles.
bool stl_is_binary(const fs::path& path, std::string_view text) {
  const std::uint64_t size = text.size();
  if (size >= kStlHeaderBytes) {
    std::uint32_t count = 0;
    std::memcpy(&count, text.data() + 80, sizeof count);  // little-endian on every target
    if (size == kStlHeaderBytes + kStlTriangleBytes * count) {
      if (count == 0)
        fail(path, "binary STL contains no triangles");
      return true;
    }
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    const bool says_solid =
        first != std::string_view::npos && lowercase(std::string(text.substr(first, 5))) == "solid";
    if (says_solid)
      return false;
    fail(path, "binary STL header announces " + std::to_string(count) + " triangles (" +
                   std::to_string(kStlHeaderBytes + kStlTriangleBytes * count) +
                   " bytes) but the file has " + std::to_string(size) +
                   " bytes: the file is truncated or not an STL file");
  }
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos)
    fail(path, "the file contains only white space");
  if (lowercase(std::string(text.substr(first, 5))) != "solid")
    fail(path, "too short for a binary STL (" + std::to_string(size) +
                   " bytes) and not an ASCII STL (no 'solid' keyword)");
  return false;
}

/// Binary STL coordinates must be finite; checked before OpenMesh merges corners (its
/// merging compares coordinates, which NaN would break).
void check_binary_stl_coordinates(const fs::path& path, std::string_view text) {
  std::uint32_t count = 0;
  std::memcpy(&count, text.data() + 80, sizeof count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* facet = text.data() + kStlHeaderBytes + kStlTriangleBytes * t;
    for (int k = 0; k < 9; ++k) {
      float value;
      std::memcpy(&value, facet + 12 + 4 * k, sizeof value);  // skip the stored normal
      if (!std::isfinite(value)) {
        std::ostringstream msg;
        msg << "triangle " << t << " has a non-finite coordinate (" << value
            << "): the file is corrupt";
        fail(path, msg.str());
      }
    }
  }
}

/// Binary or ASCII STL through OpenMesh's STL reader (which merges exactly equal corners),
/// after the checks above. OpenMesh reads the file again by its path.
void read_stl(const fs::path& path, const std::string& text, TriangleSoup& soup) {
  std::size_t facets = 0;
  if (stl_is_binary(path, text)) {
    soup.format = "binary STL";
    check_binary_stl_coordinates(path, text);
    std::uint32_t count = 0;
    std::memcpy(&count, text.data() + 80, sizeof count);
    facets = count;
  } else {
    soup.format = "ASCII STL";
    facets = lint_ascii_stl(path, text);
  }

  SoupImporter importer;
  bool ok = false;
  {
    const QuietOpenMesh quiet;
    OpenMesh::IO::Options options;
    ok = OpenMesh::IO::IOManager().read(path.string(), importer, options);
  }
  if (!ok)
    fail(path, "cannot be parsed as " + soup.format + ": the file is malformed");
  if (importer.bad_index >= 0)
    fail(path, "a face refers to vertex number " + std::to_string(importer.bad_index + 1) +
                   " (counting from 1) but the file has only " +
                   std::to_string(importer.points.size()) + " vertices");

  soup.vertices.resize(static_cast<Eigen::Index>(importer.points.size()), 3);
  for (std::size_t v = 0; v < importer.points.size(); ++v) {
    const Eigen::Vector3d& p = importer.points[v];
    if (!p.allFinite()) {
      std::ostringstream msg;
      msg << "vertex " << v << " has a non-finite coordinate (" << p.x() << ", " << p.y() << ", "
          << p.z() << "): the file is corrupt";
      fail(path, msg.str());
    }
    soup.vertices.row(static_cast<Eigen::Index>(v)) = p.transpose();
  }
  soup.faces.resize(static_cast<Eigen::Index>(importer.triangles.size()), 3);
  for (std::size_t f = 0; f < importer.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      soup.faces(static_cast<Eigen::Index>(f), k) =
          importer.triangles[f][static_cast<std::size_t>(k)];
  soup.collapsed_faces_dropped =
      importer.short_faces + facets - std::min(facets, importer.triangles.size());
  soup.corners_in_file = 3 * facets;
}

/// Splits polygons into triangle fans from their first corner: exact for convex planar
/// polygons, which is what OBJ/OFF/PLY exporters write; it is reported so the user knows it
/// happened. Polygons with fewer than three corners are dropped and counted.
void triangulate(const fs::path& path, const detail::PolygonSoup& polygons, TriangleSoup& soup) {
  // Eigen's index matrices hold int; a file this large would need tens of gigabytes anyway.
  constexpr auto kMaxIndex = static_cast<std::size_t>(std::numeric_limits<int>::max());
  if (polygons.points.size() > kMaxIndex)
    fail(path, "more than " + std::to_string(kMaxIndex) + " vertices: the file is too large");
  std::size_t triangles = 0;
  for (std::size_t k = 0; k < polygons.num_polygons(); ++k) {
    const std::size_t corners = polygons.start[k + 1] - polygons.start[k];
    if (corners < 3) {
      ++soup.collapsed_faces_dropped;
      continue;
    }
    triangles += corners - 2;
    if (corners > 3) {
      ++soup.polygons_triangulated;
      soup.triangles_from_polygons += corners - 2;
    }
  }
  if (triangles > kMaxIndex)
    fail(path, "more than " + std::to_string(kMaxIndex) + " triangles: the file is too large");

  soup.vertices.resize(static_cast<Eigen::Index>(polygons.points.size()), 3);
  for (std::size_t v = 0; v < polygons.points.size(); ++v)
    soup.vertices.row(static_cast<Eigen::Index>(v)) = polygons.points[v].transpose();
  soup.faces.resize(static_cast<Eigen::Index>(triangles), 3);
  Eigen::Index row = 0;
  for (std::size_t k = 0; k < polygons.num_polygons(); ++k) {
    const std::size_t first = polygons.start[k], end = polygons.start[k + 1];
    for (std::size_t c = first + 1; c + 1 < end; ++c, ++row)
      soup.faces.row(row) << static_cast<int>(polygons.corners[first]),
          static_cast<int>(polygons.corners[c]), static_cast<int>(polygons.corners[c + 1]);
  }
  soup.corners_in_file = 3 * triangles;
}

}  // namespace

TriangleSoup read_triangle_soup(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    fail(path, "no such file");
  if (fs::is_directory(status))
    fail(path, "is a directory, not a mesh file");
  if (!fs::is_regular_file(status)) {
    struct stat info {};
    refuse_non_regular(path, ::stat(path.c_str(), &info) == 0 ? info.st_mode : mode_t{0});
  }

  const std::string extension = lowercase(path.extension().string());
  TriangleSoup soup;
  if (extension == ".stl")
    soup.format = "STL";
  else if (extension == ".obj")
    soup.format = "OBJ";
  else if (extension == ".off")
    soup.format = "OFF";
  else if (extension == ".ply")
    soup.format = "PLY";
  else if (extension == ".3mf")
    soup.format = "3MF";
  else
    fail(path, "unsupported file extension '" + path.extension().string() +
                   "': use .stl, .obj, .off, .ply or .3mf");

  const std::string text = read_all(path);
  if (text.empty())
    fail(path, "the file is empty");

  if (soup.format == "STL") {
    read_stl(path, text, soup);
  } else if (soup.format == "3MF") {
    detail::read_3mf(path, text, soup);
  } else {
    const detail::PolygonSoup polygons = soup.format == "OBJ"   ? detail::read_obj(path, text)
                                         : soup.format == "OFF" ? detail::read_off(path, text)
                                                                : detail::read_ply(path, text);
    triangulate(path, polygons, soup);
  }
  if (soup.faces.rows() == 0)
    fail(path, "the file contains no triangles");
  return soup;
}

void write_binary_stl(const fs::path& path, const Eigen::MatrixX3d& vertices,
                      const Eigen::MatrixX3i& faces) {
  std::ofstream out(path, std::ios::binary);
  if (!out)
    fail(path, std::string("cannot be opened for writing: ") + std::strerror(errno));
  std::array<char, 80> header{};
  const char title[] = "bemshape binary STL";
  std::memcpy(header.data(), title, sizeof title - 1);
  out.write(header.data(), header.size());
  const auto count = static_cast<std::uint32_t>(faces.rows());
  out.write(reinterpret_cast<const char*>(&count), sizeof count);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)),
                          c = vertices.row(faces(f, 2));
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() > 0.0)
      n.normalize();
    std::array<float, 12> values{};
    for (int k = 0; k < 3; ++k) {
      values[static_cast<std::size_t>(k)] = static_cast<float>(n(k));
      values[static_cast<std::size_t>(3 + k)] = static_cast<float>(a(k));
      values[static_cast<std::size_t>(6 + k)] = static_cast<float>(b(k));
      values[static_cast<std::size_t>(9 + k)] = static_cast<float>(c(k));
    }
    out.write(reinterpret_cast<const char*>(values.data()), sizeof(float) * values.size());
    const std::uint16_t attribute = 0;
    out.write(reinterpret_cast<const char*>(&attribute), sizeof attribute);
  }
  if (!out)
    fail(path, "write error");
}

}  // namespace bemshape::geometry
