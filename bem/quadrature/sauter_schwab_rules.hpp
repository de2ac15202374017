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
// Every map is linear in ξ: (x̂, ŷ)(ξ, η) = ξ·(x̂, ŷ)(1, η), Jacobian ξ³·J(1, η). The rules
// below are therefore the angular part only, a tensor n-point Gauss–Legendre rule on
// [0, 1]³ in (η1, η2, η3) at ξ = 1:
//
//   ∫_{T̂} ∫_{T̂} F(x̂, ŷ) dŷ dx̂ = Σ_q w_q ∫_0^1 ξ³ F(ξ x̂_q, ξ ŷ_q) dξ,
//
// and the caller integrates over ξ: in closed form for the kernels of the Galerkin entries,
// which depend on x − y only (bem/quadrature/radial_moments.hpp), so that a rule costs 6n³, 5n³ or 2n³
// kernel evaluations instead of n times as many. It converges geometrically in n;
// bem/operators/galerkin_operators.hpp picks n per kernel from the errors measured in
// docs/quadrature.md.
//
// Weights include the Jacobians at ξ = 1 and sum to 4|T̂|² = 1 (∫_0^1 ξ³ dξ = ¼; checked by
// the tests, which also integrate polynomials exactly).

#include <vector>

namespace bemshape::bem {

enum class TouchingKind { coincident, common_edge, common_vertex };

/// Nodes (x̂, ŷ) ∈ T̂ × T̂ at ξ = 1 and weights, stored by component for the assembly's inner
/// loop.
struct SauterSchwabRule {
  std::vector<double> x1, x2, y1, y2, weight;
  int size() const { return static_cast<int>(weight.size()); }
};

/// The cached rule of `kind` with n Gauss points per angular direction of [0, 1]³ (1 ≤ n ≤ 16;
/// InternalError otherwise). Sizes: 6n³, 5n³, 2n³ points.
const SauterSchwabRule& sauter_schwab_rule(TouchingKind kind, int n);

}  // namespace bemshape::bem
