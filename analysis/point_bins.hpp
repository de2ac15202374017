#pragma once
// Points binned in cubes of a given side, for the neighbours of a point within a radius of
// the order of that side: the mid-surface points across a wall (analysis/mid_surface_pairs),
// the faces of a skin within a disc (analysis/separation_at_scale).

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace bemshape::analysis {

/// The rows of `points` (#P×3 [model units]) that `used` marks and are finite, binned in
/// cubes of side `cell`.
class PointBins {
 public:
  PointBins(const Eigen::MatrixX3d& points, const Eigen::Array<bool, Eigen::Dynamic, 1>& used,
            double cell)
      : cell_(cell) {
    for (Eigen::Index i = 0; i < points.rows(); ++i)
      if (used(i) && points.row(i).allFinite())
        cells_[key(index(points.row(i).transpose()))].push_back(i);
  }

  /// Calls visit(i) for every point in the cubes within `radius` of x (a superset of the
  /// points within `radius`: the caller checks the distance).
  template <class Visit>
  void near(const Eigen::Vector3d& x, double radius, Visit&& visit) const {
    const std::array<std::int64_t, 3> c = index(x);
    const auto reach = static_cast<std::int64_t>(std::ceil(radius / cell_));
    for (std::int64_t i = c[0] - reach; i <= c[0] + reach; ++i)
      for (std::int64_t j = c[1] - reach; j <= c[1] + reach; ++j)
        for (std::int64_t k = c[2] - reach; k <= c[2] + reach; ++k) {
          const auto found = cells_.find(key({i, j, k}));
          if (found != cells_.end())
            for (const Eigen::Index p : found->second) visit(p);
        }
  }

 private:
  std::array<std::int64_t, 3> index(const Eigen::Vector3d& x) const {
    return {static_cast<std::int64_t>(std::floor(x.x() / cell_)),
            static_cast<std::int64_t>(std::floor(x.y() / cell_)),
            static_cast<std::int64_t>(std::floor(x.z() / cell_))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    // 21 bits per axis: distinct for |index| < 2²⁰, a hash collision beyond (the lookup
    // still checks distances).
    constexpr std::uint64_t mask = (1u << 21) - 1;
    return (std::uint64_t(c[0]) & mask) | ((std::uint64_t(c[1]) & mask) << 21) |
           ((std::uint64_t(c[2]) & mask) << 42);
  }

  double cell_;
  std::unordered_map<std::uint64_t, std::vector<Eigen::Index>> cells_;
};

}  // namespace bemshape::analysis
