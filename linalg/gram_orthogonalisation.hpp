#pragma once
// Orthogonal columns by the eigenvectors of their Gram matrix, with deflation: the rotation
// that makes the columns of a tall matrix C orthogonal, i.e. C's singular vectors and values,
// at the cost of forming CᵀC and one product C X instead of a singular value decomposition
// of C. Used by the recompression of the cross approximation
// (bem/hmatrix/adaptive_cross_approximation.hpp) and by the cluster bases of the H² far
// field (bem/hmatrix/nested_far_field.hpp).

#include <Eigen/Core>

namespace bemshape::linalg {

/// Which eigenvalues of a Gram matrix are resolved again, on their own columns: rounding of
/// CᵀC, about u·λ_max (u = 2⁻⁵³), turns each eigenvector by about u·λ_max/gap, which moves
/// about u²·λ_max²/λ of squared norm between a column of eigenvalue λ and the columns of
/// eigenvalues near rounding. That is at most 1 % of what the truncation may drop, ε²·λ_max,
/// for λ ≥ 100·u²/ε²·λ_max: those columns' norms are right, the ones below are rotated again
/// (their rounding is relative to their own largest, so the same bound holds at every level).
/// 1.2e−14 at ε = 1e−8, 1.2e−6 at ε = 1e−12.
double resolved_eigenvalues(double epsilon);

/// Rotates c ← c X, w ← w X (X orthogonal) until the columns of c are orthogonal: then c's
/// columns are σᵢ times B's left singular vectors and w's the right ones, for c = B w on
/// entry. One rotation is the eigenvectors X of the Gram matrix cᵀc, five times cheaper
/// than an SVD of c for 20–30 columns. The eigenvectors are accurate only for eigenvalues
/// well above the rounding of cᵀc, about 1e−16 of the largest, that is for singular values
/// above 1e−8 of the largest; the columns below `resolved` times the largest eigenvalue
/// (resolved_eigenvalues) are rotated again by the eigenvectors of their own Gram matrix,
/// whose rounding is relative to their own size (deflation), until what is left is within
/// `negligible2` (squared norm, nothing that could be kept) or a single column.
void orthogonalise_columns(Eigen::Ref<Eigen::MatrixXd> c, Eigen::Ref<Eigen::MatrixXd> w,
                           double negligible2, double resolved);

}  // namespace bemshape::linalg
