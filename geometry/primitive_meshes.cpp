#include "geometry/primitive_meshes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace bemshape::geometry {
namespace {

using Triangles = std::vector<std::array<int, 3>>;

/// Appends triangle (a, b, c), reversed if its normal does not point along `outward`.
void add_oriented(Triangles& tris, const std::vector<Eigen::Vector3d>& pts, int a, int b, int c,
                  const Eigen::Vector3d& outward) {
  const Eigen::Vector3d n = (pts[b] - pts[a]).cross(pts[c] - pts[a]);
  if (n.dot(outward) >= 0.0)
    tris.push_back({a, b, c});
  else
    tris.push_back({a, c, b});
}

SurfaceMesh to_mesh(const std::vector<Eigen::Vector3d>& pts, const Triangles& tris) {
  Eigen::MatrixX3d v(static_cast<Eigen::Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i)
    v.row(static_cast<Eigen::Index>(i)) = pts[i];
  Eigen::MatrixX3i f(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i)
    f.row(static_cast<Eigen::Index>(i)) << tris[i][0], tris[i][1], tris[i][2];
  return SurfaceMesh(std::move(v), std::move(f));
}

void require_positive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw InputError(std::string(what) + " must be a positive number");
}

}  // namespace

SurfaceMesh make_geodesic_sphere(double radius, int frequency, const Eigen::Vector3d& center) {
  require_positive(radius, "sphere radius");
  if (frequency < 1)
    throw InputError("geodesic sphere frequency must be at least 1");
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  const std::array<Eigen::Vector3d, 12> ico = {
      Eigen::Vector3d(-1, phi, 0),  Eigen::Vector3d(1, phi, 0),   Eigen::Vector3d(-1, -phi, 0),
      Eigen::Vector3d(1, -phi, 0),  Eigen::Vector3d(0, -1, phi),  Eigen::Vector3d(0, 1, phi),
      Eigen::Vector3d(0, -1, -phi), Eigen::Vector3d(0, 1, -phi),  Eigen::Vector3d(phi, 0, -1),
      Eigen::Vector3d(phi, 0, 1),   Eigen::Vector3d(-phi, 0, -1), Eigen::Vector3d(-phi, 0, 1)};
  const std::array<std::array<int, 3>, 20> ico_faces = {
      {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
       {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
       {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}}};
  const int n = frequency;
  // A lattice point of an icosahedron face is identified exactly by its integer barycentric
  // weights on the icosahedron's corner vertices, so points on shared edges coincide.
  using Key = std::array<int, 6>;
  std::map<Key, int> index_of;
  std::vector<Eigen::Vector3d> pts;
  auto point = [&](int ia, int wa, int ib, int wb, int ic, int wc) {
    // Corners with weight zero do not identify the point: mask them before sorting.
    std::array<std::pair<int, int>, 3> w = {
        {{wa > 0 ? ia : -1, wa}, {wb > 0 ? ib : -1, wb}, {wc > 0 ? ic : -1, wc}}};
    std::sort(w.begin(), w.end());
    Key key{};
    for (int k = 0; k < 3; ++k) {
      key[2 * k] = w[k].first;
      key[2 * k + 1] = w[k].second;
    }
    auto [it, inserted] = index_of.try_emplace(key, static_cast<int>(pts.size()));
    if (inserted) {
      const Eigen::Vector3d p = (wa * ico[ia] + wb * ico[ib] + wc * ico[ic]) / n;
      pts.push_back(center + radius * p.normalized());
    }
    return it->second;
  };
  Triangles tris;
  for (const auto& face : ico_faces) {
    const int a = face[0], b = face[1], c = face[2];
    auto p = [&](int i, int j) { return point(a, n - i - j, b, i, c, j); };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        const int p0 = p(i, j), p1 = p(i + 1, j), p2 = p(i, j + 1);
        add_oriented(tris, pts, p0, p1, p2, (pts[p0] + pts[p1] + pts[p2]) / 3.0 - center);
        if (i + j < n - 1) {
          const int p3 = p(i + 1, j + 1);
          add_oriented(tris, pts, p1, p3, p2, (pts[p1] + pts[p3] + pts[p2]) / 3.0 - center);
        }
      }
    }
  }
  return to_mesh(pts, tris);
}

int geodesic_frequency_for_edge(double radius, double max_edge) {
  require_positive(radius, "sphere radius");
  require_positive(max_edge, "maximum edge length");
  // The longest edge of a frequency-n geodesic sphere is close to 1.3·R/n (measured over
  // n = 1…64); search upward from that estimate for the first frequency that satisfies it.
  int n = std::max(1, static_cast<int>(std::floor(1.0 * radius / max_edge)));
  while (make_geodesic_sphere(radius, n).max_edge_length() > max_edge)
    ++n;
  return n;
}

SurfaceMesh make_spherical_shell(double inner_radius, double outer_radius, int inner_frequency,
                                 int outer_frequency) {
  require_positive(inner_radius, "inner radius");
  if (!(outer_radius > inner_radius))
    throw InputError("spherical shell: the outer radius must exceed the inner radius");
  return concatenated(
      make_geodesic_sphere(outer_radius, outer_frequency),
      with_flipped_orientation(make_geodesic_sphere(inner_radius, inner_frequency)));
}

SurfaceMesh make_hollow_box(const Eigen::Vector3d& half, double wall, double max_edge) {
  if (!(wall > 0.0 && wall < half.minCoeff()))
    throw InputError("hollow box: the wall thickness must be positive and less than the smallest half extent");
  const Eigen::Vector3d inner = half - Eigen::Vector3d::Constant(wall);
  return concatenated(make_box(-half, half, max_edge),
                      with_flipped_orientation(make_box(-inner, inner, max_edge)));
}

SurfaceMesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double max_edge) {
  require_positive(max_edge, "maximum edge length");
  const Eigen::Vector3d extent = hi - lo;
  if (!(extent.minCoeff() > 0.0))
    throw InputError("box: hi must exceed lo in every coordinate");
  std::array<int, 3> cells;
  for (int d = 0; d < 3; ++d)
    cells[d] = std::max(1, static_cast<int>(std::ceil(extent(d) / max_edge - 1e-9)));
  // Surface vertices are lattice points (i, j, k) of the box grid; the key identifies them
  // exactly across the six faces.
  std::map<std::array<int, 3>, int> index_of;
  std::vector<Eigen::Vector3d> pts;
  auto vertex = [&](std::array<int, 3> ijk) {
    auto [it, inserted] = index_of.try_emplace(ijk, static_cast<int>(pts.size()));
    if (inserted) {
      Eigen::Vector3d p;
      for (int d = 0; d < 3; ++d)
        p(d) = ijk[d] == cells[d] ? hi(d) : lo(d) + extent(d) * ijk[d] / cells[d];
      pts.push_back(p);
    }
    return it->second;
  };
  Triangles tris;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      Eigen::Vector3d outward = Eigen::Vector3d::Zero();
      outward(axis) = side == 0 ? -1.0 : 1.0;
      for (int i = 0; i < cells[u]; ++i) {
        for (int j = 0; j < cells[v]; ++j) {
          auto at = [&](int di, int dj) {
            std::array<int, 3> ijk{};
            ijk[axis] = side == 0 ? 0 : cells[axis];
            ijk[u] = i + di;
            ijk[v] = j + dj;
            return vertex(ijk);
          };
          const int p00 = at(0, 0), p10 = at(1, 0), p01 = at(0, 1), p11 = at(1, 1);
          // Alternate the diagonal (a "union jack" pattern) so the mesh has no preferred
          // direction within a face.
          if ((i + j) % 2 == 0) {
            add_oriented(tris, pts, p00, p10, p11, outward);
            add_oriented(tris, pts, p00, p11, p01, outward);
          } else {
            add_oriented(tris, pts, p00, p10, p01, outward);
            add_oriented(tris, pts, p10, p11, p01, outward);
          }
        }
      }
    }
  }
  return to_mesh(pts, tris);
}

SurfaceMesh make_cylinder(double radius, double length, double max_edge) {
  require_positive(radius, "cylinder radius");
  require_positive(length, "cylinder length");
  require_positive(max_edge, "maximum edge length");
  constexpr double two_pi = 2.0 * std::numbers::pi;
  const int n_theta = std::max(8, static_cast<int>(std::ceil(two_pi * radius / max_edge)));
  // Rows of the side are about as far apart as an equilateral triangle is high.
  const int n_z =
      std::max(1, static_cast<int>(std::ceil(length / (max_edge * std::sqrt(3.0) / 2.0))));
  std::vector<Eigen::Vector3d> pts;
  Triangles tris;
  // Side rings; odd rows are rotated by half a step so the side triangles are near-equilateral.
  std::vector<std::vector<int>> rows(n_z + 1);
  std::vector<double> row_offset(n_z + 1);
  for (int k = 0; k <= n_z; ++k) {
    const double z = -0.5 * length + length * k / n_z;
    row_offset[k] = (k % 2) * 0.5 * two_pi / n_theta;
    for (int m = 0; m < n_theta; ++m) {
      const double t = row_offset[k] + two_pi * m / n_theta;
      rows[k].push_back(static_cast<int>(pts.size()));
      pts.emplace_back(radius * std::cos(t), radius * std::sin(t), z);
    }
  }
  // Joins two closed rings (angles increasing, starting at the given offsets) by a strip of
  // triangles, always advancing along the ring whose next point comes first in angle.
  auto stitch = [&](const std::vector<int>& a, double a0, const std::vector<int>& b, double b0,
                    const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& outward_at) {
    const size_t na = a.size(), nb = b.size();
    size_t i = 0, j = 0;
    auto angle_a = [&](size_t i) { return a0 + two_pi * static_cast<double>(i) / na; };
    auto angle_b = [&](size_t j) { return b0 + two_pi * static_cast<double>(j) / nb; };
    while (i < na || j < nb) {
      const int ai = a[i % na], bj = b[j % nb];
      if (j >= nb || (i < na && angle_a(i + 1) < angle_b(j + 1))) {
        const int an = a[(i + 1) % na];
        const Eigen::Vector3d c = (pts[ai] + pts[an] + pts[bj]) / 3.0;
        add_oriented(tris, pts, ai, an, bj, outward_at(c));
        ++i;
      } else {
        const int bn = b[(j + 1) % nb];
        const Eigen::Vector3d c = (pts[ai] + pts[bn] + pts[bj]) / 3.0;
        add_oriented(tris, pts, ai, bn, bj, outward_at(c));
        ++j;
      }
    }
  };
  auto radial = [](const Eigen::Vector3d& c) { return Eigen::Vector3d(c.x(), c.y(), 0.0); };
  for (int k = 0; k < n_z; ++k)
    stitch(rows[k], row_offset[k], rows[k + 1], row_offset[k + 1], radial);
  // Caps: concentric rings whose point counts shrink linearly towards a centre vertex.
  const int n_rings = std::max(1, static_cast<int>(std::ceil(radius / max_edge)));
  for (int side = 0; side < 2; ++side) {
    const double z = side == 0 ? -0.5 * length : 0.5 * length;
    const Eigen::Vector3d axial(0.0, 0.0, side == 0 ? -1.0 : 1.0);
    auto cap_normal = [&](const Eigen::Vector3d&) { return axial; };
    std::vector<int> outer = side == 0 ? rows.front() : rows.back();
    double outer_offset = side == 0 ? row_offset.front() : row_offset.back();
    for (int ring = n_rings - 1; ring >= 1; --ring) {
      const double r = radius * ring / n_rings;
      const int count =
          std::max(3, static_cast<int>(std::lround(n_theta * double(ring) / n_rings)));
      std::vector<int> inner;
      for (int m = 0; m < count; ++m) {
        const double t = two_pi * m / count;
        inner.push_back(static_cast<int>(pts.size()));
        pts.emplace_back(r * std::cos(t), r * std::sin(t), z);
      }
      stitch(inner, 0.0, outer, outer_offset, cap_normal);
      outer = std::move(inner);
      outer_offset = 0.0;
    }
    const int centre = static_cast<int>(pts.size());
    pts.emplace_back(0.0, 0.0, z);
    for (size_t m = 0; m < outer.size(); ++m)
      add_oriented(tris, pts, centre, outer[m], outer[(m + 1) % outer.size()], axial);
  }
  return to_mesh(pts, tris);
}

}  // namespace bemshape::geometry
