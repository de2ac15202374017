#include "tests/support/damaged_meshes.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "geometry/constructive_solids.hpp"
#include "geometry/primitive_meshes.hpp"

namespace bemshape::testing {
namespace {

using Eigen::Vector3d;
using geometry::SurfaceMesh;

constexpr double kPi = std::numbers::pi;

/// The faces of `mesh` reversed if its signed volume is negative.
SurfaceMesh outward(SurfaceMesh mesh) {
  return mesh.signed_volume() < 0.0 ? geometry::with_flipped_orientation(mesh) : mesh;
}

void set_mesh(DamagedMesh& d, const SurfaceMesh& mesh) {
  d.vertices = mesh.vertices();
  d.faces = mesh.faces();
}

/// The nodal cubic x = s(t² − 1), y = s·t(t² − 1), z = lift·t for t ∈ [−t_end, t_end]: a
/// loop like the letter α that crosses itself at right angles at the origin (t = ±1), the
/// two passes `2·lift` apart in height so that their faces do not lie on each other.
std::vector<Vector3d> alpha_path(double s, double lift, double t_end, int points) {
  std::vector<Vector3d> path;
  for (int i = 0; i <= points; ++i) {
    const double t = -t_end + 2.0 * t_end * i / points;
    path.emplace_back(s * (t * t - 1.0), s * t * (t * t - 1.0), lift * t);
  }
  return path;
}

/// Bernoulli's lemniscate of half-width a, z = lift·sin t: a figure eight crossing itself at
/// the origin (t = π/2, 3π/2) at right angles, the passes 2·lift apart in height. Closed.
std::vector<Vector3d> lemniscate_path(double a, double lift, int points) {
  std::vector<Vector3d> path;
  for (int i = 0; i < points; ++i) {
    const double t = 2.0 * kPi * i / points;
    const double d = 1.0 + std::sin(t) * std::sin(t);
    path.emplace_back(a * std::cos(t) / d, a * std::sin(t) * std::cos(t) / d, lift * std::sin(t));
  }
  return path;
}

DamagedMesh crossing_flap() {
  DamagedMesh d;
  d.name = "crossing_flap";
  d.description =
      "a bar 0.3 wide and 0.25 high bent into a loop like the letter alpha, its end passing "
      "through its start at right angles: one shell crossing itself";
  const double width = 0.3, height = 0.25;
  const std::vector<Vector3d> path = alpha_path(1.5, 0.05, 1.5, 120);
  set_mesh(d, swept_bar(path, false, width, height));
  // The two halves, meeting at t = 0 (the loop's far end), do not cross themselves; their
  // union is the part the bar describes.
  d.intact = geometry::mesh_union(swept_bar_part(path, false, width, height, 0, 60),
                                  swept_bar_part(path, false, width, height, 60, 120));
  d.site = Vector3d::Zero();
  d.size = std::sqrt(2.0 * 2.0 * width * width + (height + 0.1) * (height + 0.1));
  d.outcome = DamageOutcome::resolved;
  d.wall = std::min(width, height);
  d.h0 = d.wall;
  d.max_edge = 0.5 * d.wall;
  return d;
}

DamagedMesh crossing_link() {
  DamagedMesh d;
  d.name = "crossing_link";
  d.description =
      "a connecting-rod-like link: a closed bar 0.3 wide and 0.25 high along a figure eight "
      "4 across, crossing itself in the middle (the crossing about 5 % of the diagonal)";
  const double width = 0.3, height = 0.25;
  const std::vector<Vector3d> path = lemniscate_path(2.0, 0.05, 160);
  set_mesh(d, swept_bar(path, true, width, height));
  // Halves from lobe tip to lobe tip (t = 0 to π and π to 2π): each passes the middle once.
  d.intact = geometry::mesh_union(swept_bar_part(path, true, width, height, 0, 80),
                                  swept_bar_part(path, true, width, height, 80, 160));
  d.site = Vector3d::Zero();
  d.size = std::sqrt(2.0 * 2.0 * width * width + (height + 0.1) * (height + 0.1));
  d.outcome = DamageOutcome::resolved;
  d.wall = std::min(width, height);
  d.h0 = d.wall;
  d.max_edge = 0.5 * d.wall;
  return d;
}

}  // namespace

SurfaceMesh swept_bar(const std::vector<Vector3d>& path, bool closed, double width, double height) {
  const int n = static_cast<int>(path.size());
  return swept_bar_part(path, closed, width, height, 0, closed ? n : n - 1);
}

SurfaceMesh swept_bar_part(const std::vector<Vector3d>& path, bool closed, double width,
                           double height, int first, int last) {
  const auto n = static_cast<int>(path.size());
  // The section at every path point, from the whole path's directions.
  Eigen::MatrixX3d ring(4 * n, 3);
  for (int i = 0; i < n; ++i) {
    const Vector3d before =
        path[static_cast<std::size_t>(closed ? (i + n - 1) % n : std::max(i - 1, 0))];
    const Vector3d after =
        path[static_cast<std::size_t>(closed ? (i + 1) % n : std::min(i + 1, n - 1))];
    const Vector3d tangent = (after - before).normalized();
    const Vector3d side = tangent.cross(Vector3d::UnitZ()).normalized();
    const Vector3d up = side.cross(tangent);
    const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; ++k)
      ring.row(4 * i + k) = (path[static_cast<std::size_t>(i)] +
                             0.5 * width * corners[k][0] * side + 0.5 * height * corners[k][1] * up)
                                .transpose();
  }
  // A whole closed path is a tube; anything else a bar with end caps.
  const bool tube = closed && last - first == n;
  const int sections = tube ? n : last - first + 1;
  Eigen::MatrixX3d v(4 * sections, 3);
  for (int i = 0; i < sections; ++i)
    v.middleRows(4 * i, 4) = ring.middleRows(4 * ((first + i) % n), 4);
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i < (tube ? sections : sections - 1); ++i) {
    const int a = 4 * i, b = 4 * ((i + 1) % sections);
    for (int k = 0; k < 4; ++k) {
      const int p = a + k, q = a + (k + 1) % 4, p2 = b + k, q2 = b + (k + 1) % 4;
      f.emplace_back(p, q, q2);
      f.emplace_back(p, q2, p2);
    }
  }
  if (!tube) {
    const int e = 4 * (sections - 1);
    f.emplace_back(0, 3, 2);
    f.emplace_back(0, 2, 1);
    f.emplace_back(e, e + 1, e + 2);
    f.emplace_back(e, e + 2, e + 3);
  }
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    faces.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return outward(SurfaceMesh(std::move(v), std::move(faces)));
}

const char* to_string(DamageOutcome outcome) {
  switch (outcome) {
    case DamageOutcome::resolved:
      return "resolved";
    case DamageOutcome::united:
      return "united";
    case DamageOutcome::measured_around:
      return "measured around";
  }
  return "";
}

std::vector<DamagedMesh> damaged_meshes() {
  return {crossing_flap(), crossing_link()};
}

DamagedMesh damaged_mesh(const std::string& name) {
  std::string names;
  for (DamagedMesh& d : damaged_meshes()) {
    if (d.name == name)
      return d;
    names += (names.empty() ? "" : ", ") + d.name;
  }
  throw std::invalid_argument("no damaged mesh '" + name + "'; the corpus has " + names);
}

}  // namespace bemshape::testing
