#pragma once
// Taylor coefficients of the inverse distance 1/|R| in three dimensions, for the Cartesian
// multipole expansions of bem/evaluate/laplace_treecode.hpp:
//
//   b_β(R) = ∂_R^β (1/|R|) / β!,   β = (β1, β2, β3) ∈ ℕ³, |β| = β1 + β2 + β3 ≤ degree,
//
// so that 1/|R − d| = Σ_β b_β(R) (−d)^β for |d| < |R| (the Taylor series in d about 0) and
// ∂_{R_k} b_β = (β_k + 1) b_{β+e_k}.
//
// The coefficients follow from the recurrence used by the Cartesian treecodes of Lindsay &
// Krasny (J. Comput. Phys. 172 (2001) 879) and Duan & Krasny (J. Comput. Chem. 22 (2001) 184),
// here for the plain Coulomb kernel (tests/bem/evaluate/test_inverse_distance_taylor.cpp
// checks it against closed-form derivatives)
//
//   |β| |R|² b_β + (2|β| − 1) Σ_i R_i b_{β−e_i} + (|β| − 1) Σ_i b_{β−2e_i} = 0,
//
// with b_0 = 1/|R| and terms whose multi-index has a negative component omitted: O(1) work
// per coefficient, (degree+1)(degree+2)(degree+3)/6 coefficients in all. Units: b_β has
// [1/model units^(|β|+1)].
//
// Multi-indices are numbered by total degree, then lexicographically (β1 descending, then
// β2 descending): the coefficients of degree ≤ p are the first
// MultiIndexTable::count(p) entries, whatever the table's own degree, so an expansion can be
// truncated at any order below the table's by using a prefix.

#include <array>
#include <vector>

#include <Eigen/Core>

namespace bemshape::bem {

class MultiIndexTable {
 public:
  /// Every multi-index with |β| ≤ degree (degree ≥ 0).
  explicit MultiIndexTable(int degree);

  /// Number of multi-indices with |β| ≤ p: (p+1)(p+2)(p+3)/6.
  static constexpr int count(int p) { return (p + 1) * (p + 2) * (p + 3) / 6; }

  int degree() const { return degree_; }
  int size() const { return static_cast<int>(exponents_.size()); }
  /// β of entry k.
  const std::array<int, 3>& exponent(int k) const { return exponents_[static_cast<size_t>(k)]; }
  /// Entry of β − e_i (−1 if β_i = 0).
  int lower(int k, int i) const { return lower_[static_cast<size_t>(k)][static_cast<size_t>(i)]; }
  /// Entry of β − 2e_i (−1 if β_i < 2).
  int lower2(int k, int i) const { return lower2_[static_cast<size_t>(k)][static_cast<size_t>(i)]; }
  /// Entry of β + e_i (−1 if |β| = degree).
  int raise(int k, int i) const { return raise_[static_cast<size_t>(k)][static_cast<size_t>(i)]; }
  /// Entry of β (−1 if |β| > degree).
  int index(int b1, int b2, int b3) const;

  /// The recurrence of entry k ≥ 1 without branches: indices of β − e_i and β − 2e_i, with
  /// size() (a slot holding 0) for the missing ones, and the factors (2|β| − 1)/|β| and
  /// (|β| − 1)/|β|.
  struct RecurrenceStep {
    std::array<int, 3> lower, lower2;
    double first, second;
  };
  const std::vector<RecurrenceStep>& recurrence() const { return recurrence_; }

 private:
  int degree_;
  std::vector<std::array<int, 3>> exponents_;
  std::vector<std::array<int, 3>> lower_, lower2_, raise_;
  std::vector<RecurrenceStep> recurrence_;
};

/// b_β(R) for the first MultiIndexTable::count(degree) entries of `table` (degree ≤
/// table.degree()), written to b[0 .. count(degree)); b must hold table.size() + 1 values,
/// the last of which is set to 0 (the slot missing terms of the recurrence read). R ≠ 0.
void inverse_distance_taylor(const MultiIndexTable& table, const Eigen::Vector3d& R, int degree,
                             double* b);

}  // namespace bemshape::bem
