#pragma once
// Singularity-adapted 4-D quadrature for pairs of flat triangles that touch (Sauter–Schwab):
//
//   ∫_{T̂} ∫_{T̂} F(x̂, ŷ) dŷ dx̂ ≈ Σ_q w_q F(x̂_q, ŷ_q),   T̂ = {(t1, t2): 0 ≤ t2 ≤ t1 ≤ 1},
//
// for integrands F that are smooth except where the two triangles' points meet. The reference
// triangle T̂ has corners (0, 0), (1, 0), (1, 1); the affine map of a physical triangle with
// corners (A, B, C) is χ(t) = A + t1 (B − A) + t2 (C − B), Jacobian 2|T|. The pair must be
// presented with its shared corners first and in the same order in both triangles:
//
//   coincident:     the same corners A, B, C in both;
//   common edge:    A and B shared (the edge t2 = 0 of T̂);
//   common vertex:  A shared (the corner t = 0 of T̂).
//
// Each case splits T̂ × T̂ into sub-domains (6, 5 and 2) and maps [0, 1]⁴ onto each so that
// |x − y| becomes ξ·η1 (or ξ) times a function bounded away from zero; the Jacobian of the map
// (ξ³η1²η2, ξ³η1², ξ³η1²η2, ξ³η2) cancels a kernel singularity of order |x − y|^{−2} and the
// transformed integrand is analytic. The regions and maps are those of S. A. Sauter and
// C. Schwab, Boundary Element Methods (Springer 2011), Sec. 5.2.
//
// Every map is linear in ξ: (x̂, ŷ)(ξ, η) = ξ·(x̂, ŷ)(1, η), Jacobian ξ³·J(1, η). In the
// common-edge maps x − y is moreover proportional to ξη1, in the coincident ones to ξη1η2
// (bem/quadrature/radial_moments.hpp), with the Jacobian's powers ξ³η1² and ξ³η1²η2. For the
// entries of the Galerkin operators with piecewise-constant functions, whose kernels depend
// on x − y only, the caller integrates those m leading variables in closed form, and a rule
// is a tensor n-point Gauss–Legendre rule in the 4 − m others with the leading ones at 1:
//
//   ∫_{T̂} ∫_{T̂} F(x̂ − ŷ) dŷ dx̂ = Σ_q w_q ∫_0^1 w_m(u) F(u (x̂_q − ŷ_q)) du,
//
// m = 1 (vertex; 2n³ points), 2 (edge; 5n²) or 3 (coincident; 6n). The exact direction takes
// the boundary layer of e^{−κ|x − y|} along x − y out of the points: the coincident and edge
// rules need few points at any κ·diameter. bem/operators/galerkin_operators.hpp picks n per
// kernel from the errors measured in docs/quadrature.md.
//
// Weights include the Jacobians' remaining factors; Σ_q w_q ∫_0^1 w_m(u) du = 4|T̂|² = 1
// (checked by the tests, which also integrate polynomials exactly with the m = 1 rules and
// polynomials of x̂ − ŷ with the others).

#include <vector>

namespace bemshape::bem {

enum class TouchingKind { coincident, common_edge, common_vertex };

/// Nodes (x̂, ŷ) ∈ T̂ × T̂ with the m leading variables at 1, and weights, stored by
/// component for the assembly's inner loop.
struct SauterSchwabRule {
  std::vector<double> x1, x2, y1, y2, weight;
  int closed_form_variables = 1;  ///< m: the leading variables the caller integrates
  int size() const { return static_cast<int>(weight.size()); }
};

/// The most variables a rule of `kind` may leave to the closed form: 3 (coincident), 2
/// (common edge), 1 (common vertex).
constexpr int max_closed_form_variables(TouchingKind kind) {
  return kind == TouchingKind::coincident ? 3 : kind == TouchingKind::common_edge ? 2 : 1;
}

/// The cached rule of `kind` with n Gauss points per remaining direction (1 ≤ n ≤ 16) and m
/// variables in closed form (1 ≤ m ≤ max_closed_form_variables(kind)); InternalError
/// otherwise. Size: (6, 5 or 2 sub-domains)·n^(4−m) points.
const SauterSchwabRule& sauter_schwab_rule(TouchingKind kind, int n, int m);

/// The rule the Galerkin entries use: m = max_closed_form_variables(kind).
inline const SauterSchwabRule& sauter_schwab_rule(TouchingKind kind, int n) {
  return sauter_schwab_rule(kind, n, max_closed_form_variables(kind));
}

}  // namespace bemshape::bem
