#pragma once
// Thickness functions of the shape-feature solution s (paper, section "Thickness function").
//
//   f_h = h0²·div s·χ = h0²·(λ1 + … + λd)·χ        inverse thickness [dimensionless]
//   h_f = h0·(1/f_h − a)·χ                          paper thickness [model units]
//   h_p = h0·(1/(h0²·λd) − a)·χ                     principal thickness [model units]
//
// h_f is exact on plates and gives about D/2 on a round rod and D/3 on a ball of diameter D,
// because it sums the gradient of s over all directions. h_p uses only the largest
// eigenvalue of the feature tensor (the direction across the wall): it equals the plate
// thickness on plates and about D + 0.5·a·h0 on a rod and D + a·h0 on a ball, i.e. the
// diameter of the largest inscribed sphere, which is what a CAD wall-thickness check means.
// docs/theory.md derives both.
//
// Degenerate values: where f_h (or h0²λd) is not above kMinInverseThickness — far from any
// wall, at re-entrant corners, or outside the solid — the thickness is not measurable and
// saturates at kMaxThicknessFactor·h0 instead of becoming infinite or NaN.

#include <algorithm>

namespace bemshape::features {

/// Smallest inverse thickness taken at face value. 1e-6 corresponds to a wall a million
/// times h0, beyond anything the PDE resolves (s decays over h0), so nothing measurable is
/// lost by saturating there.
inline constexpr double kMinInverseThickness = 1e-6;
/// Thickness reported where the inverse thickness is not above kMinInverseThickness.
inline constexpr double kMaxThicknessFactor = 1.0 / kMinInverseThickness;

/// h0·(1/f − a) for f > kMinInverseThickness, else kMaxThicknessFactor·h0. Never below 0:
/// f > 1/a would mean a wall thinner than zero (only numerical noise produces it).
inline double thickness_from_inverse(double inverse_thickness, double h0, double a) {
  if (!(inverse_thickness > kMinInverseThickness)) return kMaxThicknessFactor * h0;
  return std::max(0.0, h0 * (1.0 / inverse_thickness - a));
}

/// f_h = h0²·trace(∇s) (χ = 1 assumed: callers pass only points inside the solid).
inline double inverse_thickness(double divergence_s, double h0) { return h0 * h0 * divergence_s; }

/// h_f = h0(1/f_h − a).
inline double paper_thickness(double f_h, double h0, double a) {
  return thickness_from_inverse(f_h, h0, a);
}

/// h_p = h0(1/(h0²λd) − a) from the largest eigenvalue λd of the feature tensor.
inline double principal_thickness(double lambda_max, double h0, double a) {
  return thickness_from_inverse(h0 * h0 * lambda_max, h0, a);
}

}  // namespace bemshape::features
