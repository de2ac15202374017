#pragma once
// The block partition of an N×N operator over a cluster tree (bem/hmatrix/cluster_tree.hpp):
// the leaves of the block tree built from (root, root) by splitting both clusters until a pair
// is admissible or a cluster is a leaf.
//
// Admissibility (the standard condition for asymptotically smooth kernels):
//   min(diam τ, diam σ) ≤ η · dist(τ, σ)
// with diam and dist of the clusters' bounding boxes. An admissible block is approximated by
// a low-rank product (bem/hmatrix/adaptive_cross_approximation.hpp); the others are
// stored densely.

#include <vector>

#include "bem/hmatrix/cluster_tree.hpp"

namespace bemshape::bem {

struct BlockIndex {
  int rows = 0;  ///< cluster index of τ (test panels)
  int cols = 0;  ///< cluster index of σ (trial panels)
};

struct BlockPartition {
  std::vector<BlockIndex> admissible;  ///< far-field blocks, low rank
  std::vector<BlockIndex> dense;       ///< near-field blocks
};

/// Default η. Measured on the fast path's Laplace operator [−K0 | V0] (sphere of 9680
/// faces, leaves of 32, ε = 1e−8; `bench_fast_path sphere 10000 hmatrix --eta H`): η = 1, 2, 4
/// store 178, 98, 79 MB of near field and 278, 244, 208 MB of low-rank factors, with the
/// same GMRES iterations. At 100820 faces (`bench_fast_path sphere 100000 hmatrix --eta H`)
/// η = 4 against 2: peak memory 3.99 GB against 4.46, the same 9 iterations, f_h error
/// (3.424e−5) and CPU time (128 s). Against the dense solution η = 4 gives the differences
/// of η = 2 (thin-walled box of 7152 faces: φ 4.3e−7, q 2.5e−6, thickness 3.5e−6; sphere of
/// 3920: φ 2.2e−7, q 2.3e−5; docs/benchmarks.md): the cross approximation stays within ε on
/// blocks a quarter of their size apart.
inline constexpr double kDefaultAdmissibility = 4.0;

/// Blocks of a square operator on one tree.
BlockPartition partition_blocks(const ClusterTree& tree, double eta = kDefaultAdmissibility);
/// Blocks of an operator from the elements of `col_tree` to those of `row_tree` (e.g. from
/// panels to target points); BlockIndex::rows indexes row_tree, ::cols col_tree.
BlockPartition partition_blocks(const ClusterTree& row_tree, const ClusterTree& col_tree,
                                double eta = kDefaultAdmissibility);

}  // namespace bemshape::bem
