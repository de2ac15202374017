#pragma once
// Fast solver of the shape-feature transmission problem: the same P0 Galerkin system as the
// dense reference (bem/solve/dense_transmission_solver.hpp),
//
//   [ −½M − K0    V0 ] [φ]   [ 0    ]
//   [  ½M − Kκ    Vκ ] [q] = [ Vκ g ],   g = n_i/ã,
//
// with the Laplace block row [−K0 | V0] as a hierarchical matrix compressed by adaptive
// cross approximation (bem/hmatrix/hierarchical_matrix.hpp; on large meshes its far
// field between large clusters in the H² form, bem/hmatrix/nested_far_field.hpp,
// HMatrixSolverOptions::far_field), the Yukawa block row as a
// sparse near-field matrix (bem/solve/yukawa_near_field.hpp; the exponential decay
// makes it exactly as sparse as the dense path's own dropping rule), and restarted GMRES
// (linalg/gmres.hpp) with a two-level preconditioner: a coarse space of
// cluster-wise constant densities (bem/solve/cluster_coarse_space.hpp), then LU of
// the system restricted to clusters (bem/solve/cluster_block_preconditioner.hpp).
// Storage and work are O(N log N). docs/benchmarks.md holds the measured times, memory and
// iteration counts.

#include <cstdint>
#include <optional>
#include <vector>

#include "bem/solve/boundary_solution.hpp"
#include "bem/hmatrix/block_partition.hpp"
#include "bem/solve/cluster_block_preconditioner.hpp"
#include "bem/solve/cluster_coarse_space.hpp"
#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/quadrature/panel.hpp"
#include "linalg/gmres.hpp"
#include "core/progress.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::bem {

/// The GMRES tolerance from which the operators are stored in single precision
/// (HMatrixSolverOptions::single_precision): their rounding perturbs a product by about
/// 4e−7, below a residual of 1e−6, above a tighter one.
inline constexpr double kSinglePrecisionStorageTolerance = 1e-6;

/// The GMRES tolerance from which the single-precision entries (HMatrixSolverOptions::
/// single_precision) are also computed to kSinglePrecisionRuleAccuracy only.
inline constexpr double kSinglePrecisionEntriesTolerance = 1e-6;

struct HMatrixSolverOptions {
  /// Relative residual GMRES must reach (`--tolerance`), preconditioned on the side
  /// `preconditioner_side` names: by default ‖M⁻¹(b − A x)‖/‖M⁻¹b‖, which tracks the
  /// relative error of the densities φ and q (see preconditioner_side).
  double tolerance = 1e-6;
  /// ε of the cross approximation: two digits below the GMRES tolerance, so compression
  /// errors stay below what the solve leaves.
  double aca_tolerance = 1e-8;
  /// η of the admissibility condition.
  double eta = kDefaultAdmissibility;
  /// The interior H-matrix in single precision, low-rank factors and dense near-field blocks
  /// (HierarchicalMatrixOptions), the factors' columns of small singular value in 16- or
  /// 8-bit fixed point within the same rounding bound (AdaptivePrecisionFactors), and the
  /// exterior values in single precision: under half the memory. Rounding the factors
  /// perturbs a product by about 4e−7 relative, the near field by less (measured,
  /// tests/bem/hmatrix), which leaves the solution unchanged at the default tolerance
  /// of 1e−6 (docs/benchmarks.md) but would dominate a tighter one: turn it off below
  /// kSinglePrecisionStorageTolerance (analysis/boundary_solve.cpp does).
  bool single_precision = true;
  /// Panels per leaf of the cluster tree.
  Eigen::Index leaf_size = ClusterTree::kDefaultLeafSize;
  /// Panels per preconditioner block.
  Eigen::Index preconditioner_block = ClusterBlockPreconditioner::kDefaultBlockSize;
  /// Panels per cluster of the coarse space (bem/solve/cluster_coarse_space.hpp);
  /// 0 = the blocks alone (block Jacobi: more iterations, growing with N).
  Eigen::Index coarse_cluster = ClusterCoarseSpace::kDefaultClusterSize;
  /// GMRES restart length. Where the Krylov bases would not fit in the memory allowed, the
  /// solver takes a shorter one, in steps of 10 down to 30, and reports it
  /// (SolveReport::restart).
  int restart = 60;
  int max_iterations = 600;
  /// The preconditioner's side in GMRES (linalg/gmres.hpp), which sets what
  /// `tolerance` bounds. Left: the preconditioned residual, an estimate of the densities'
  /// relative error because the two-level preconditioner is close to A⁻¹. Right: the
  /// residual of the equations, which lets q's error grow with the condition number of the
  /// first-kind single layer (about 30 × the residual on a 5120-face ball, 1.2e−5 against the
  /// dense path at 1e−6 on 2000 faces, against 1.0e−6 preconditioned on the left; the
  /// left side takes 14 iterations there instead of 11; docs/benchmarks.md).
  linalg::PreconditionerSide preconditioner_side = linalg::PreconditionerSide::left;
  /// How the Laplace row's far field is kept. `hmatrix`: every admissible block as its own
  /// factors. `nested`: the blocks between clusters of at least `nested_min_cluster` panels
  /// in the H² form (bem/hmatrix/nested_far_field.hpp: bases shared by a cluster's
  /// blocks, built from the kernel without holding those blocks' factors), the smaller
  /// ones as factors; less memory, a second cross approximation of the large blocks (time).
  /// `automatic`: `nested` where the H-matrix would not fit in the memory allowed.
  enum class FarField { automatic, hmatrix, nested };
  FarField far_field = FarField::automatic;
  /// Smallest cluster of a block kept in the H² form [panels]. Below, a block's own
  /// narrow-format factors take fewer bytes than its coupling between shared bases
  /// (measured on a 100820-face sphere, docs/benchmarks.md: 128, 256 and 512 panels give
  /// 704, 686 and 713 MB of far field against the H-matrix's 1001 MB).
  Eigen::Index nested_min_cluster = 256;
  /// Upper bound on the process's resident size while it solves [bytes]
  /// (core/memory_watch.hpp, resident_memory_limit_bytes); 0 = what the machine has.
  std::uint64_t max_memory_bytes = 0;
  /// What the process holds besides the solver, counted into the estimate [bytes]; empty:
  /// its resident size when the estimate is made (tests set it to make the estimate exact).
  std::optional<std::uint64_t> held_bytes;
  /// Stop after the memory check: the result holds only report.memory_estimate_bytes (and
  /// unknowns). analysis::solve_boundary confirms with it that a mesh a refusal names fits.
  bool estimate_only = false;
};

/// The admissible blocks of the Laplace row split by how `--far-field nested` keeps them:
/// `nested`, in the H² form, the blocks between clusters of at least
/// options.nested_min_cluster panels that do not lie inside one preconditioner block (the
/// preconditioner reads its blocks from the H-matrix, HierarchicalMatrix::diagonal_blocks);
/// `factored`, the rest, as the H-matrix's own factors.
struct FarFieldSplit {
  std::vector<BlockIndex> nested, factored;
};
FarFieldSplit split_far_field(const ClusterTree& tree, const std::vector<BlockIndex>& admissible,
                              const HMatrixSolverOptions& options);

/// Sheets of surface each cluster of `tree` holds (index as tree.clusters()): its panels'
/// area over the product of its box's two largest extents, in [1, 4]. A patch of one smooth
/// sheet reads 1 (up to √2 where it runs diagonally through its box), a cluster holding both
/// skins of a wall thinner than itself 2, a corner of three walls 3. A far-field block's rank
/// grows with the sheets its clusters hold.
std::vector<double> cluster_sheets(const ClusterTree& tree, const std::vector<Panel>& panels);

/// What the block partition of the Laplace row holds, counted before anything is assembled
/// (count_partition): the part of the memory estimate that depends on the geometry (thin
/// walls have both sides of the wall in many near-field blocks, and clusters that hold two
/// sheets of surface need about twice the rank of one).
struct HMatrixPartitionCounts {
  double near_entries = 0.0;  ///< Σ over dense blocks of o·|τ| × g·|σ| (o = 1, g = 2)
  double admissible_edges = 0.0;  ///< Σ over admissible blocks of o·|τ| + g·|σ|
  double largest_admissible_edge = 0.0;  ///< the largest o·|τ| + g·|σ| of one block
  /// With the far field nested (split_far_field): Σ over the factored blocks of their edge
  /// o·|τ| + g·|σ| times kSmallBlockSheetRank per sheet of the block's clusters, and the H²
  /// part's entries at rank kNestedSheetRank per sheet of each cluster (capped by its rows;
  /// sheets: the cluster's own, cluster_sheets, or those the whole near field reads if more):
  /// the leaves' bases and the transfer matrices on both sides, and one coupling per nested
  /// block.
  double factored_rank_edges = 0.0;
  double nested_basis_entries = 0.0, nested_coupling_entries = 0.0;
};

/// The counts of `partition` on `tree` (built over `panels`) for the Laplace row [−K0 | V0],
/// the nested split of `options` included.
HMatrixPartitionCounts count_partition(const ClusterTree& tree, const BlockPartition& partition,
                                       const std::vector<Panel>& panels,
                                       const HMatrixSolverOptions& options);

/// Bytes the fast path holds at its peak for `faces` faces, as an upper bound: the near
/// field (exact, from `counts`), the low-rank factors at
/// kBoundRank per block edge (nested: the factored blocks and the H² part at their counted
/// ranks per sheet), the exterior matrix of `exterior_pairs` panel pairs in
/// `exterior_runs` runs (yukawa_near_field_rows counts them), the preconditioner and coarse
/// space, the Krylov bases of options.restart steps and the product's work arrays, the
/// cross approximation's work arrays on every thread, all times kPeakSafetyFactor (measured,
/// docs/reliability.md, "Estimate and peak"), plus `held_bytes` (what the process holds
/// already: the meshes, panels, cluster tree). The far field kept as `far_field`: hmatrix,
/// nested, or automatic for options.far_field (its own automatic taken as hmatrix).
std::uint64_t hmatrix_solver_memory_estimate(
    Eigen::Index faces, std::uint64_t exterior_pairs, std::uint64_t exterior_runs,
    const HMatrixSolverOptions& options,
    HMatrixSolverOptions::FarField far_field, const HMatrixPartitionCounts& counts,
    std::uint64_t held_bytes = 0);

/// Bytes the fast path needs at least for `faces` faces, whatever the geometry: the
/// preconditioner's factors and the Krylov bases at the shortest restart the guard may
/// choose. A check before remeshing: a mesh of that many faces cannot fit below it.
std::uint64_t hmatrix_solver_minimum_bytes(Eigen::Index faces, const HMatrixSolverOptions& options);

/// Solves for s_1, s_2, s_3 on a closed, outward-oriented mesh. Throws ResourceError if the
/// estimate does not fit and NumericalError if GMRES does not reach the tolerance or the
/// solution is not finite. The report's `iterations` is the largest count of the three
/// directions.
BoundarySolution solve_transmission_hmatrix(const geometry::SurfaceMesh& mesh,
                                            const TransmissionParameters& parameters,
                                            const HMatrixSolverOptions& options = {},
                                            const ProgressCallback& progress = {});

}  // namespace bemshape::bem
