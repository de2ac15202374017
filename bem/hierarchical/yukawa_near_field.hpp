#pragma once
// The exterior (Yukawa) operators as one sparse matrix. Gκ = e^{−κr}/(4πr) decays
// exponentially, so a Galerkin entry between panels whose gap exceeds
// g* = −ln(YukawaAttenuation::negligible)/κ ≈ 23/κ is below 1e−10 of an unattenuated
// entry and is zero in the dense path too (bem/galerkin_operators.hpp): with that threshold
// storing only the rest loses nothing the dense path keeps; the H-matrix solver derives the
// threshold from its compression tolerance instead. A panel interacts with the panels within about
// g* + its size, O(1) of them per row whatever N, so the matrix has O(N) entries.
//
// Layout, in cluster-tree order (bem/hierarchical/cluster_tree.hpp): N × 2N,
//   Y(i, j) = −Kκ[i, j],   Y(i, N + j) = Vκ[i, j],
// i.e. the exterior identity's operator on (φ, q) without the ½M term.

#include <cstdint>

#include <Eigen/SparseCore>

#include "bem/galerkin_operators.hpp"
#include "bem/hierarchical/cluster_tree.hpp"
#include "bem/panel.hpp"
#include "core/progress.hpp"

namespace bemshape::bem {

/// 32-bit column indices: 12 bytes per stored entry instead of 16. The entries are O(N)
/// (about 1300 per row at the default element size), so 2^31 − 1 of them is ample up to
/// 10⁶ faces; assembly refuses a matrix with more.
template <class Scalar>
using SparseRowMatrixOf = Eigen::SparseMatrix<Scalar, Eigen::RowMajor, std::int32_t>;
using SparseRowMatrix = SparseRowMatrixOf<double>;
/// The H-matrix solver's exterior matrix when its factors are in single precision
/// (tolerance ≥ 1e−6): 8 bytes per entry instead of 12. The entries' rounding, 6e−8
/// relative, is that of the single-precision near field and factors of the interior part.
using SparseRowMatrixSingle = SparseRowMatrixOf<float>;

/// The gap beyond which Yukawa entries attenuated below `negligible` are dropped,
/// g* = −ln(negligible)/κ [model units].
double yukawa_cutoff_gap(double kappa, double negligible);

/// The number of entries each row of Y will hold, in tree order: two (Kκ, Vκ) per panel
/// within the cutoff (a bound: Kκ vanishes between coplanar panels). The candidate search
/// only, no integrals: what the memory guard needs before anything is assembled. About
/// 1300 per row at the default element size κ·h = 3 on a curved surface; it grows as
/// (κ·h)^−2 on finer meshes and doubles on walls thinner than the cutoff.
Eigen::VectorX<Eigen::Index> yukawa_near_field_row_sizes(const std::vector<Panel>& panels,
                                                         const ClusterTree& tree, double kappa,
                                                         double negligible);

/// Assembles Y for the panels in tree order (parallel over rows; each row is computed the
/// same way whatever the thread count). Entries between panels whose gap
/// |c_j − c_k| − r_j − r_k gives e^{−κ·gap} < `negligible` are dropped; the default is the
/// dense path's threshold, larger values (the H-matrix solver passes ε) trade entries
/// below the compression tolerance for fewer nonzeros. If the counted entries do not fit in
/// the memory the machine has left (core/memory.hpp), ResourceError before any is stored.
/// The result is uncompressed (Eigen's term): each row owns the room counted for it, and
/// nonZeros() counts the entries actually stored; see stored_bytes.
/// `row_sizes`: yukawa_near_field_row_sizes of the same arguments, if already counted.
/// Bytes a matrix from assemble_yukawa_near_field holds: a value and a 32-bit column per
/// slot (used or not) and the row offsets.
template <class Scalar>
std::uint64_t stored_bytes(const SparseRowMatrixOf<Scalar>& y) {
  return (sizeof(Scalar) + 4ull) * std::uint64_t(y.data().allocatedSize()) +
         8ull * std::uint64_t(y.outerSize());
}

/// `Scalar`: double, or float for the single-precision matrix (each entry is computed in
/// double precision and rounded once when stored).
template <class Scalar = double>
SparseRowMatrixOf<Scalar> assemble_yukawa_near_field(
    const std::vector<Panel>& panels, const ClusterTree& tree, double kappa,
    double negligible = YukawaAttenuation::negligible, const ProgressCallback& progress = {},
    const Eigen::VectorX<Eigen::Index>* row_sizes = nullptr);

}  // namespace bemshape::bem
