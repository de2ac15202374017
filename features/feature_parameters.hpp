#pragma once
// Parameters of the shape-feature functions (Yamada, "Geometric shape features extraction
// using a steady state partial differential equation system", section "Formulation").

namespace bemshape::features {

struct FeatureParameters {
  /// h0: characteristic length [model units], about the smallest thickness of interest.
  double h0 = 1.0;
  /// a: dimensionless diffusion parameter (paper's default 0.2); ã = a·h0², α = 4/a.
  double a = 0.2;
  /// w: half-width of the skeleton band [model units]: a point belongs to the skeleton when
  /// its distance to the mid-surface, |s̃|/λ, is at most w. Callers pass the grid spacing
  /// (the paper's suggestion, "e.g. the pixel size").
  double skeleton_width = 0.0;

  double a_tilde() const { return a * h0 * h0; }
  double alpha() const { return 4.0 / a; }
  /// κ = √(α/ã) = 2/(a·h0) [1/model units]: decay rate of s outside the solid.
  double kappa() const { return 2.0 / (a * h0); }
};

/// Throws InputError unless h0 > 0, a > 0, w ≥ 0 and all are finite.
void validate(const FeatureParameters& parameters);

}  // namespace bemshape::features
