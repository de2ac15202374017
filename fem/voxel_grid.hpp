#pragma once
// The regular grid of the voxel finite-element solver: square (2-D) or cubic (3-D) cells of
// side `cell_size` [model units] over the box [origin, origin + cells·cell_size], and the
// solid's characteristic function χ per cell.
//
// Indexing (x fastest):
//   cell (c_0, …, c_{D−1}), 0 ≤ c_d < cells[d]     → Σ_d c_d·Π_{e<d} cells[e]
//   node (p_0, …, p_{D−1}), 0 ≤ p_d ≤ cells[d]     → Σ_d p_d·Π_{e<d} (cells[e] + 1)
// Cell c spans [origin + c·h, origin + (c + 1)·h]; node p sits at origin + p·h. Nodes with
// some p_d ∈ {0, cells[d]} lie on ∂Ω_R, where s = 0.
//
// χ is stored as a float in [0, 1] per cell: 0 or 1 for a binary image or a centre inside
// test, the covered volume fraction when the indicator was sampled at several points per
// cell (see characteristic_function.hpp).

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "features/feature_parameters.hpp"

namespace bemshape::fem {

using GridIndex = std::int64_t;

template <int D>
struct VoxelGrid {
  static_assert(D == 2 || D == 3, "the voxel solver is 2-D or 3-D");
  using Point = Eigen::Matrix<double, D, 1>;

  std::array<GridIndex, D> cells{};  ///< number of cells along each axis
  double cell_size = 0.0;            ///< h [model units]
  Point origin = Point::Zero();      ///< lower corner of Ω_R [model units]
  std::vector<float> chi;            ///< #cells χ ∈ [0, 1] (empty until filled)

  GridIndex num_cells() const {
    GridIndex n = 1;
    for (int d = 0; d < D; ++d)
      n *= cells[d];
    return n;
  }
  GridIndex num_nodes() const {
    GridIndex n = 1;
    for (int d = 0; d < D; ++d)
      n *= cells[d] + 1;
    return n;
  }
  /// Centre of cell `c` (multi-index) [model units].
  Point cell_centre(const std::array<GridIndex, D>& c) const {
    Point x;
    for (int d = 0; d < D; ++d)
      x(d) = origin(d) + (static_cast<double>(c[d]) + 0.5) * cell_size;
    return x;
  }
  /// Position of node `p` (multi-index) [model units].
  Point node_position(const std::array<GridIndex, D>& p) const {
    Point x;
    for (int d = 0; d < D; ++d)
      x(d) = origin(d) + static_cast<double>(p[d]) * cell_size;
    return x;
  }
  /// Multi-index of cell number `index`.
  std::array<GridIndex, D> cell_multi_index(GridIndex index) const {
    std::array<GridIndex, D> c{};
    for (int d = 0; d < D; ++d) {
      c[d] = index % cells[d];
      index /= cells[d];
    }
    return c;
  }
  GridIndex cell_index(const std::array<GridIndex, D>& c) const {
    GridIndex index = 0;
    for (int d = D - 1; d >= 0; --d)
      index = index * cells[d] + c[d];
    return index;
  }
  GridIndex node_index(const std::array<GridIndex, D>& p) const {
    GridIndex index = 0;
    for (int d = D - 1; d >= 0; --d)
      index = index * (cells[d] + 1) + p[d];
    return index;
  }
  /// Upper corner of Ω_R [model units].
  Point upper_corner() const {
    Point x = origin;
    for (int d = 0; d < D; ++d)
      x(d) += static_cast<double>(cells[d]) * cell_size;
    return x;
  }
};

/// The margin left around the solid's bounding box: max(h0, 12/κ) [model units]. s decays
/// like e^{−κ·dist} outside the solid, so at 12/κ the Dirichlet condition s = 0 on ∂Ω_R
/// perturbs the solution by about e^{−12} ≈ 6e−6 of its size; h0 keeps at least one
/// characteristic length of exterior around thin parts when a is large.
double required_margin(const features::FeatureParameters& parameters);

/// Cell counts divisible by this power of two let the multigrid hierarchy halve the grid
/// until its coarsest level has at most about kMaxCoarseNodes nodes (see multigrid.hpp).
/// Returns for each axis the smallest count ≥ `needed[d]` (and ≥ 2) of the form m·2^k with a
/// common k chosen so that Π_d (m_d + 1) ≤ max_coarse_nodes.
template <int D>
std::array<GridIndex, D> multigrid_friendly_cells(const std::array<GridIndex, D>& needed,
                                                  GridIndex max_coarse_nodes);

/// An empty grid (χ not filled) with cells of side `cell_size` covering [lo, hi] plus at
/// least required_margin(parameters) on every side; the counts are rounded up by
/// multigrid_friendly_cells and the extra cells shared equally on both sides, so the box
/// stays centred on the solid. With `align_to_lo` the grid lines pass through `lo` (used
/// for images, so that cells and pixels share boundaries when one size divides the other).
/// Throws InputError for a non-positive or non-finite cell size or box, ResourceError when
/// the grid would exceed `max_cells`.
template <int D>
VoxelGrid<D> grid_around(const Eigen::Matrix<double, D, 1>& lo,
                         const Eigen::Matrix<double, D, 1>& hi, double cell_size,
                         const features::FeatureParameters& parameters, GridIndex max_cells,
                         bool align_to_lo = false);

/// Default limit on the number of cells of one grid, so that a mistyped cell size is refused
/// before allocating instead of exhausting memory: at the measured cost per cell
/// (kRunBytesPerCell) both limits correspond to about 3 GB. Callers with more memory pass a
/// larger limit.
template <int D>
inline constexpr GridIndex kDefaultMaxCells = D == 2 ? 12'000'000 : 9'000'000;

/// Peak memory of a whole `bemshape fem` run [bytes] on a grid of `cells` cells (χ,
/// coefficient, load and solution with D columns, CG and multigrid vectors on every level,
/// feature fields, output copies, and the process itself), for its --max-memory guard
/// (analysis/memory_budget.hpp): kRunBaseBytes + kRunBytesPerCell<D> × cells. Measured peak RSS
/// with OMP_NUM_THREADS=1 fits 10 MB + 285-290 bytes per cell in 3-D (a ball: 36³ cells 25 MB,
/// 56³ 60 MB, 96³ 260 MB, 112³ 409 MB) and 15 MB + 215 bytes per cell in 2-D (an L-shaped
/// PNG: 864² 175 MB, 1728² 656 MB); the constants are rounded up from these.
inline constexpr double kRunBaseBytes = 16e6;
template <int D>
inline constexpr double kRunBytesPerCell = D == 2 ? 240.0 : 310.0;
template <int D>
double estimated_run_bytes(GridIndex cells) {
  return kRunBaseBytes + kRunBytesPerCell<D> * static_cast<double>(cells);
}

}  // namespace bemshape::fem
