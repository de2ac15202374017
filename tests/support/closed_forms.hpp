#pragma once
// Closed-form solutions of the shape-feature PDE (docs/theory.md derives each one):
//   −div(ã ∇s_i − e_i χ) + α(1−χ) s_i = 0,  ã = a·h0²,  α = 4/a,  κ = √(α/ã) = 2/(a·h0).
// Inside the solid s is harmonic, outside it solves Δs = κ²s; across the surface s is
// continuous and ∂_n s(inside) − ∂_n s(outside) = n_i/ã.
// For radially symmetric solids s = ψ(r)·x̂ (ball, shell) or ψ(ρ)·(x, y, 0)/ρ (rod), so every
// reference reduces to a profile ψ. All lengths in model units; s is in model units too
// (s ~ 1/(ã·κ) ~ h0).

#include <Eigen/Core>

namespace bemshape::testing {

/// The PDE's parameters: h0 the characteristic length, a the dimensionless diffusion.
struct PdeParameters {
  double h0 = 0.3;
  double a = 0.2;
  double a_tilde() const { return a * h0 * h0; }
  double alpha() const { return 4.0 / a; }
  double kappa() const { return 2.0 / (a * h0); }
};

/// Inverse thickness f_h = h0²·div s from the solution's divergence.
inline double inverse_thickness(const PdeParameters& p, double divergence) {
  return p.h0 * p.h0 * divergence;
}
/// Paper thickness h_f = h0(1/f_h − a).
inline double paper_thickness(const PdeParameters& p, double f_h) {
  return p.h0 * (1.0 / f_h - p.a);
}
/// Principal thickness h_p = h0(1/(h0²λ_max) − a).
inline double principal_thickness(const PdeParameters& p, double lambda_max) {
  return p.h0 * (1.0 / (p.h0 * p.h0 * lambda_max) - p.a);
}

/// Ball of radius R: s = A·x inside with A = 1/(ã(2 + z + 1/(1+z))), z = κR; outside
/// ψ = D·k1(κr), k1(z) = e^{−z}(1+z)/z².
struct BallSolution {
  double A = 0, D = 0, radius = 0, kappa = 0;
  /// ψ(r) for r ≥ 0 (inside and outside).
  double psi(double r) const;
  /// s(x) at any point.
  Eigen::Vector3d s(const Eigen::Vector3d& x) const;
};
BallSolution ball_solution(const PdeParameters& p, double radius);

/// Spherical shell R1 < r < R2 (cavity r < R1): ψ = A r + B/r² in the solid, C·i1(κr) in the
/// cavity, D·k1(κr) outside, with i1(z) = (z cosh z − sinh z)/z². div s = 3A in the solid.
struct ShellSolution {
  double A = 0, B = 0, C = 0, D = 0, inner_radius = 0, outer_radius = 0, kappa = 0;
  double psi(double r) const;
  /// dψ/dr on the solid side (R1 ≤ r ≤ R2).
  double dpsi_solid(double r) const { return A - 2.0 * B / (r * r * r); }
  Eigen::Vector3d s(const Eigen::Vector3d& x) const;
};
ShellSolution shell_solution(const PdeParameters& p, double inner_radius, double outer_radius);

/// Plate of thickness h (1-D): s linear inside with slope 2/(ã(κh + 2)), so
/// f_h = h0²·slope and h0(1/f_h − a) = h exactly.
double plate_slope(const PdeParameters& p, double thickness);

/// Infinite round rod of radius R along z: s = A·(x, y, 0) inside with
/// A = 1/(ã(2 + z·K0(z)/K1(z))), z = κR; S = diag(A, A, 0).
double rod_slope(const PdeParameters& p, double radius);

/// Tube: the infinite cylindrical shell R1 < ρ < R2 around the z axis (a bore ρ < R1):
/// s = ψ(ρ)·(x, y, 0)/ρ with ψ = A ρ + B/ρ in the solid, C·I1(κρ) in the bore, D·K1(κρ)
/// outside. S = diag(ψ', ψ/ρ, 0) in (radial, tangential, axial); on the mid-surface ρ0 =
/// √(−B/A), where ψ changes sign, S = diag(2A, 0, 0).
struct TubeSolution {
  double A = 0, B = 0, C = 0, D = 0, inner_radius = 0, outer_radius = 0, kappa = 0;
  double psi(double rho) const;
  /// dψ/dρ on the solid side.
  double dpsi_solid(double rho) const { return A - B / (rho * rho); }
  /// ρ0 = √(−B/A), where ψ changes sign in the solid.
  double mid_radius() const;
};
TubeSolution tube_solution(const PdeParameters& p, double inner_radius, double outer_radius);

/// The paper's 1-D solution on [K, L] with s(K) = s(L) = 0 and the solid [pos, pos + h]:
/// s = c1 e^{λx} + c2 e^{−λx} left of the solid, c3 x + c4 inside, c5 e^{λx} + c6 e^{−λx}
/// right of it, λ = √(α/ã). The constants are the paper's explicit formulas (section
/// "Analytical validation in one dimension").
struct Interval1DSolution {
  double c1 = 0, c2 = 0, c3 = 0, c4 = 0, c5 = 0, c6 = 0, lambda = 0, pos = 0, h = 0;
  double s(double x) const;
};
Interval1DSolution interval_1d_solution(const PdeParameters& p, double K, double L, double pos,
                                        double h);

}  // namespace bemshape::testing
