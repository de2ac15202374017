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
// transformed integrand is analytic. A tensor n-point Gauss–Legendre rule on [0, 1]⁴ then
// converges geometrically in n; bem/galerkin_operators.hpp picks n per kernel from the errors
// measured in docs/quadrature.md. The regions and maps are those of S. A. Sauter and
// C. Schwab, Boundary Element Methods (Springer 2011), Sec. 5.2.
//
// Weights include the Jacobians of the maps and sum to |T̂|² = ¼ (checked by the tests,
// which also integrate polynomials exactly).

#include <vector>

namespace bemshape::bem {

enum class TouchingKind { coincident, common_edge, common_vertex };

/// Nodes (x̂, ŷ) ∈ T̂ × T̂ and weights, stored by component for the assembly's inner loop.
struct SauterSchwabRule {
  std::vector<double> x1, x2, y1, y2, weight;
  int size() const { return static_cast<int>(weight.size()); }
};

/// The cached rule of `kind` with n Gauss points per direction of [0, 1]⁴ (1 ≤ n ≤ 16;
/// InternalError otherwise). Sizes: 6n⁴, 5n⁴, 2n⁴ points.
const SauterSchwabRule& sauter_schwab_rule(TouchingKind kind, int n);

}  // namespace bemshape::bem
