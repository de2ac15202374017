#include "geometry/mesh_orientation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <tuple>

#include "geometry/mesh_validation.hpp"
#include "geometry/winding_number.hpp"

namespace bemshape::geometry {
namespace {

/// A point is inside another shell when its winding number with respect to that shell is
/// ±1; halfway is the natural cut, far from both values for points off the surface.
constexpr double kInsideWinding = 0.5;

struct Neighbour {
  int face;
  bool same_direction;  // both faces traverse the shared edge the same way
};

/// For each face, its neighbours across edges shared by exactly two faces.
std::vector<std::vector<Neighbour>> manifold_neighbours(const Eigen::MatrixX3i& faces) {
  struct Use {
    int lo, hi, face;
    bool forward;
  };
  std::vector<Use> uses;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      if (a != b)
        uses.push_back({std::min(a, b), std::max(a, b), static_cast<int>(f), a < b});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  std::vector<std::vector<Neighbour>> result(static_cast<std::size_t>(faces.rows()));
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi)
      ++j;
    if (j - i == 2 && uses[i].face != uses[i + 1].face) {
      const bool same = uses[i].forward == uses[i + 1].forward;
      result[static_cast<std::size_t>(uses[i].face)].push_back({uses[i + 1].face, same});
      result[static_cast<std::size_t>(uses[i + 1].face)].push_back({uses[i].face, same});
    }
    i = j;
  }
  return result;
}

void reverse(Eigen::MatrixX3i& faces, Eigen::Index f) {
  std::swap(faces(f, 1), faces(f, 2));
}

}  // namespace

ConsistentOrientation orient_consistently(const Eigen::MatrixX3d& vertices,
                                          const Eigen::MatrixX3i& faces) {
  ConsistentOrientation result;
  result.faces = faces;
  const auto neighbours = manifold_neighbours(faces);
  const std::size_t nf = static_cast<std::size_t>(faces.rows());
  std::vector<int> flip(nf, -1);  // −1 unvisited, else 0/1
  for (std::size_t seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0)
      continue;
    // Breadth-first over the patch: a neighbour sharing the edge in the same direction
    // must have the opposite flip state.
    std::vector<std::size_t> patch{seed};
    flip[seed] = 0;
    bool ok = true;
    for (std::size_t head = 0; head < patch.size(); ++head) {
      const std::size_t f = patch[head];
      for (const Neighbour& n : neighbours[f]) {
        const int wanted = flip[f] ^ (n.same_direction ? 1 : 0);
        int& state = flip[static_cast<std::size_t>(n.face)];
        if (state < 0) {
          state = wanted;
          patch.push_back(static_cast<std::size_t>(n.face));
        } else if (state != wanted) {
          ok = false;
        }
      }
    }
    if (!ok) {
      if (result.orientable)
        result.non_orientable_at = vertices.row(faces(static_cast<Eigen::Index>(seed), 0));
      result.orientable = false;
      continue;
    }
    // Flip whichever side of the patch is smaller: orientation relative to the solid is
    // decided later, so only the count of changed faces matters here.
    std::size_t flipped = 0;
    for (std::size_t f : patch)
      flipped += static_cast<std::size_t>(flip[f]);
    const bool invert = 2 * flipped > patch.size();
    for (std::size_t f : patch)
      if ((flip[f] == 1) != invert) {
        reverse(result.faces, static_cast<Eigen::Index>(f));
        ++result.faces_flipped;
      }
  }
  return result;
}

VolumeOrientation orient_to_bound_volume(const Eigen::MatrixX3d& vertices,
                                         const Eigen::MatrixX3i& faces) {
  VolumeOrientation result;
  result.faces = faces;
  std::size_t count = 0;
  const std::vector<int> label = shell_labels(faces, &count);
  std::vector<std::vector<Eigen::Index>> members(count);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    if (label[static_cast<std::size_t>(f)] >= 0)
      members[static_cast<std::size_t>(label[static_cast<std::size_t>(f)])].push_back(f);

  std::vector<Eigen::MatrixX3i> shell_faces(count);
  std::vector<Eigen::Vector3d> lo(count), hi(count);
  result.shells.resize(count);
  for (std::size_t s = 0; s < count; ++s) {
    Eigen::MatrixX3i& sf = shell_faces[s];
    sf.resize(static_cast<Eigen::Index>(members[s].size()), 3);
    double volume = 0.0, largest = -1.0;
    lo[s].setConstant(std::numeric_limits<double>::infinity());
    hi[s].setConstant(-std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < members[s].size(); ++i) {
      const Eigen::Index f = members[s][i];
      sf.row(static_cast<Eigen::Index>(i)) = faces.row(f);
      const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)),
                            c = vertices.row(faces(f, 2));
      volume += a.dot(b.cross(c)) / 6.0;
      const double area = (b - a).cross(c - a).norm();
      if (area > largest) {
        largest = area;
        result.shells[s].where = (a + b + c) / 3.0;
      }
      for (const Eigen::Vector3d* p : {&a, &b, &c}) {
        lo[s] = lo[s].cwiseMin(*p);
        hi[s] = hi[s].cwiseMax(*p);
      }
    }
    result.shells[s].faces = members[s].size();
    result.shells[s].volume = volume;
  }
  for (std::size_t s = 0; s < count; ++s) {
    const Eigen::Vector3d& p = result.shells[s].where;
    for (std::size_t t = 0; t < count; ++t) {
      if (t == s || (p.array() < lo[t].array()).any() || (p.array() > hi[t].array()).any())
        continue;
      if (std::abs(winding_number(vertices, shell_faces[t], p)) > kInsideWinding)
        ++result.shells[s].depth;
    }
    ShellOrientation& shell = result.shells[s];
    const bool want_positive = shell.depth % 2 == 0;
    if (!want_positive)
      ++result.cavities;
    if ((shell.volume > 0.0) != want_positive && shell.volume != 0.0) {
      shell.flipped = true;
      shell.volume = -shell.volume;
      ++result.shells_flipped;
      for (Eigen::Index f : members[s]) {
        reverse(result.faces, f);
        ++result.faces_flipped;
      }
    }
  }
  return result;
}

}  // namespace bemshape::geometry
