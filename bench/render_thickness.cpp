// render_thickness: a picture of a thickness map for the documentation. Reads a .vtp that
// `bemshape thickness` wrote (-o or --solver-output: points, triangles and the point array
// "thickness", raw appended binary or ASCII) and paints the surface in an oblique
// orthographic view with a z-buffer: per-pixel linear interpolation of the vertex thickness,
// coloured with viridis (apps/output/colour_map.hpp) and darkened by a Lambert factor for the
// shape, next to a colour bar labelled with its ends and middle.
//
//   render_thickness THICKNESS.vtp OUT.png [MIN MAX] [AZIMUTH_DEG ELEVATION_DEG]
//
// MIN/MAX default to the range of the thickness array.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "apps/output/colour_map.hpp"
#include "apps/output/png_writer.hpp"
#include "geometry/surface_mesh.hpp"

using namespace bemshape;

namespace {

/// The numbers of the DataArray named by `marker` (`Name="…"`) or following it: ASCII, or
/// Float64/Int64 in the raw appended block (UInt64 byte counts, little-endian).
std::vector<double> vtp_array(const std::string& xml, const std::string& marker) {
  const std::size_t at = xml.find(marker);
  if (at == std::string::npos) {
    std::cerr << "render_thickness: no " << marker << " in the .vtp\n";
    std::exit(2);
  }
  // A marker inside a DataArray tag (Name="…") names that array; otherwise take the next one.
  const bool in_tag = marker.starts_with("Name=");
  const std::size_t tag = in_tag ? xml.rfind("<DataArray", at) : xml.find("<DataArray", at);
  const std::size_t tag_end = xml.find('>', tag);
  const std::string attributes = xml.substr(tag, tag_end - tag);
  std::vector<double> values;
  if (attributes.find("format=\"appended\"") == std::string::npos) {
    std::istringstream in(xml.substr(tag_end + 1, xml.find("</DataArray>", tag_end) - tag_end - 1));
    double v;
    while (in >> v)
      values.push_back(v);
    return values;
  }
  const std::size_t offset_at = attributes.find("offset=\"") + 8;
  const std::size_t start =
      xml.find('_', xml.find("<AppendedData")) + 1 + std::stoull(attributes.substr(offset_at));
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, xml.data() + start, sizeof bytes);
  const bool integer = attributes.find("type=\"Int64\"") != std::string::npos;
  for (std::uint64_t b = 0; b < bytes; b += 8) {
    const char* p = xml.data() + start + sizeof bytes + b;
    double v = 0.0;
    if (integer) {
      std::int64_t i = 0;
      std::memcpy(&i, p, 8);
      v = static_cast<double>(i);
    } else {
      std::memcpy(&v, p, 8);
    }
    values.push_back(v);
  }
  return values;
}

std::string label(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", x);
  return buffer;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 5 && argc != 7) {
    std::cerr << "usage: render_thickness THICKNESS.vtp OUT.png [MIN MAX] [AZIMUTH ELEVATION]\n";
    return 2;
  }
  std::ifstream file(argv[1], std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  const std::string xml = text.str();
  const std::vector<double> points = vtp_array(xml, "<Points>");
  const std::vector<double> corners = vtp_array(xml, "Name=\"connectivity\"");
  const std::string point_data = xml.substr(xml.find("<PointData>"));
  const std::vector<double> values = vtp_array(point_data, "Name=\"thickness\"");
  const auto nv = static_cast<Eigen::Index>(points.size() / 3);
  const auto nf = static_cast<Eigen::Index>(corners.size() / 3);
  Eigen::MatrixX3d vertices(nv, 3);
  Eigen::MatrixX3i faces(nf, 3);
  for (Eigen::Index i = 0; i < nv; ++i)
    vertices.row(i) << points[3 * i], points[3 * i + 1], points[3 * i + 2];
  for (Eigen::Index i = 0; i < nf; ++i)
    faces.row(i) << int(corners[3 * i]), int(corners[3 * i + 1]), int(corners[3 * i + 2]);
  const geometry::SurfaceMesh mesh(vertices, faces);
  const Eigen::VectorXd thickness =
      Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  if (thickness.size() != nv) {
    std::cerr << "render_thickness: " << thickness.size() << " thickness values for " << nv
              << " points\n";
    return 2;
  }
  double lo = thickness.minCoeff(), hi = thickness.maxCoeff();
  if (argc >= 5) {
    lo = std::atof(argv[3]);
    hi = std::atof(argv[4]);
  }
  const double azimuth = (argc == 7 ? std::atof(argv[5]) : -35.0) * M_PI / 180.0;
  const double elevation = (argc == 7 ? std::atof(argv[6]) : 35.0) * M_PI / 180.0;

  // View: rotate about z by the azimuth, then tilt by the elevation; the camera looks along −z'.
  const Eigen::Matrix3d view =
      (Eigen::AngleAxisd(-(M_PI / 2 - elevation), Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(azimuth, Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  const Eigen::MatrixX3d p = (mesh.vertices() * view.transpose()).eval();
  const Eigen::Vector3d pmin = p.colwise().minCoeff(), pmax = p.colwise().maxCoeff();
  const int width = 900, bar = 150, margin = 20;
  const double scale = (width - bar - 2 * margin) / std::max(pmax.x() - pmin.x(), 1e-300);
  const int height = static_cast<int>(std::ceil((pmax.y() - pmin.y()) * scale)) + 2 * margin;
  output::RgbImage image(width, std::max(height, 260));
  std::vector<double> depth(static_cast<std::size_t>(image.width()) * image.height(),
                            -std::numeric_limits<double>::infinity());
  const Eigen::Vector3d light = Eigen::Vector3d(0.3, 0.5, 1.0).normalized();  // view frame

  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d n = view * mesh.face_normals().row(f).transpose();
    if (n.z() <= 0.0)
      continue;  // faces away from the camera
    const double shade = 0.55 + 0.45 * std::max(0.0, n.dot(light));
    Eigen::Vector2d s[3];
    double z[3], t[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index v = mesh.faces()(f, k);
      s[k] = Eigen::Vector2d(margin + (p(v, 0) - pmin.x()) * scale,
                             margin + (pmax.y() - p(v, 1)) * scale);
      z[k] = p(v, 2);
      t[k] = thickness(v);
    }
    const double area =
        (s[1] - s[0]).x() * (s[2] - s[0]).y() - (s[1] - s[0]).y() * (s[2] - s[0]).x();
    if (std::abs(area) < 1e-12)
      continue;
    const int x0 =
        std::max(0, static_cast<int>(std::floor(std::min({s[0].x(), s[1].x(), s[2].x()}))));
    const int x1 = std::min(image.width() - 1,
                            static_cast<int>(std::ceil(std::max({s[0].x(), s[1].x(), s[2].x()}))));
    const int y0 =
        std::max(0, static_cast<int>(std::floor(std::min({s[0].y(), s[1].y(), s[2].y()}))));
    const int y1 = std::min(image.height() - 1,
                            static_cast<int>(std::ceil(std::max({s[0].y(), s[1].y(), s[2].y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d q(x + 0.5, y + 0.5);
        double w[3];
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector2d a = s[(k + 1) % 3] - q, b = s[(k + 2) % 3] - q;
          w[k] = (a.x() * b.y() - a.y() * b.x()) / area;
        }
        if (w[0] < -1e-9 || w[1] < -1e-9 || w[2] < -1e-9)
          continue;
        const double zq = w[0] * z[0] + w[1] * z[1] + w[2] * z[2];
        double& zb = depth[static_cast<std::size_t>(y) * image.width() + x];
        if (zq <= zb)
          continue;
        zb = zq;
        const double tq = w[0] * t[0] + w[1] * t[1] + w[2] * t[2];
        const output::Rgb c = output::viridis((tq - lo) / (hi - lo));
        image.at(x, y) = {static_cast<std::uint8_t>(c.r * shade),
                          static_cast<std::uint8_t>(c.g * shade),
                          static_cast<std::uint8_t>(c.b * shade)};
      }
  }
  // Colour bar: top = hi, bottom = lo.
  const int bx = width - bar + 20, top = margin + 10,
            bottom = std::min(image.height() - margin, top + 220);
  for (int y = top; y < bottom; ++y)
    image.fill_rectangle(bx, y, bx + 20, y + 1,
                         output::viridis(1.0 - double(y - top) / (bottom - top - 1)));
  const output::Rgb black{0, 0, 0};
  image.draw_text(bx + 26, top, label(hi), black);
  image.draw_text(bx + 26, (top + bottom) / 2 - 5, label(0.5 * (lo + hi)), black);
  image.draw_text(bx + 26, bottom - 10, label(lo), black);
  image.write_png(argv[2]);
  std::cout << argv[2] << ": " << image.width() << " x " << image.height()
            << " pixels, colour range " << lo << " to " << hi << '\n';
  return 0;
}
