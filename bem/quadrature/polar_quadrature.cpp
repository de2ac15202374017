#include "bem/quadrature/polar_quadrature.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "bem/quadrature/gauss_legendre.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "linalg/vector_exponential.hpp"
#include "bem/kernels/yukawa_kernel.hpp"

namespace bemshape::bem {
namespace {

/// √(a² + b²) without std::hypot's overflow-safe scaling (the arguments are lengths of a
/// panel's geometry, far from overflow, and std::hypot cost 11 % of an assembly).
inline double length2d(double a, double b) { return std::sqrt(a * a + b * b); }

using Vec2 = Eigen::Vector2d;

/// The integrands in v (angle) and u (radius) are analytic in the strip |Im| < π/2; on
/// pieces of width ≤ max_piece_width an n-point Gauss–Legendre rule converges like
/// (6.4)^{−2n} there: PolarResolution's 10 points give ≈ 1e−16, and the measured error stays
/// below 1e−10 (docs/quadrature.md, table). The radial tails of the gradients always take 10.
constexpr int tail_points_per_piece = 10;
/// Widest composite piece in v or u: keeps the Bernstein-ellipse argument above valid.
constexpr double max_piece_width = 1.0;
/// Pieces double in width away from the point of the edge nearest to x, where the e^{−κρ'}
/// boundary layer and the near-singular behaviour are concentrated.
constexpr double piece_growth = 2.0;
/// An edge whose line passes closer than this fraction of the panel diameter to x' spans a
/// triangle (x', edge) of zero area up to rounding: it contributes nothing and is skipped
/// (its parametrisation t = p sinh v would divide by p ≈ 0).
constexpr double on_line_tolerance = 1e-12;
/// Targets closer than this fraction of the diameter to the panel's plane are in the plane
/// (d = 0): rounding in d of a point computed on the panel is ~1e−16·diameter, and the double
/// layer jumps by 1 across the plane, so this decides which side, or the principal value.
constexpr double in_plane_tolerance = 1e-12;
/// Yukawa only: when κ(ρ'_max − c) exceeds this, e^{−κρ'} varies by more than e across the
/// panel and the constant part of each radial closed form is integrated exactly over θ
/// (Θ e^{−κc}) instead of inside the quadrature; below it the combined form with expm1 avoids
/// the cancellation 1 − e^{−κδ} for small κδ. Either is exact in exact arithmetic.
constexpr double split_exponent = 1.0;
/// The radial tails stop where the exponential factor has decayed by e^{−45} ≈ 3e−20
/// relative to its value at the point nearest to x (far below the 1e−8 target and double
/// rounding); the angular pieces by PolarResolution::negligible_exponent.
constexpr double tail_negligible_exponent = 45.0;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Composite Gauss–Legendre over the interval between `start` and `end` (either order):
/// pieces begin at `start` with width w0 and grow by piece_growth up to max_piece_width.
/// visit(s, w) receives nodes with positive weights (the integral over the interval, whatever
/// its orientation); stop(s) is asked at the start of each piece and ends the walk when true.
template <class Visit, class Stop>
void graded_gauss(int points_per_piece, double start, double end, double w0, Visit&& visit,
                  Stop&& stop) {
  const GaussLegendreRule& gl = gauss_legendre(points_per_piece);
  const double direction = end >= start ? 1.0 : -1.0;
  const double length = std::abs(end - start);
  double position = 0.0;
  double width = std::min(w0, max_piece_width);
  while (position < length) {
    if (stop(start + direction * position)) return;
    double piece = std::min(width, length - position);
    // Merge a short remainder into this piece instead of leaving a sliver.
    if (length - position - piece < 0.25 * piece) piece = length - position;
    const double mid = start + direction * (position + 0.5 * piece);
    for (int i = 0; i < points_per_piece; ++i)
      visit(mid + direction * 0.5 * piece * gl.nodes[static_cast<size_t>(i)],
            0.5 * piece * gl.weights[static_cast<size_t>(i)]);
    position += piece;
    width = std::min(width * piece_growth, max_piece_width);
  }
}

/// Edge P1 → P2 in plane coordinates centred at x': unit direction u, foot of the
/// perpendicular F = P1 − t1 u, abscissae t1 < t2 of the ends, distance p = |F| and the
/// orientation σ of the triangle (x', P1, P2).
struct EdgeFrame {
  Vec2 foot, u;
  double p = 0, sigma = 0, t1 = 0, t2 = 0;
  double s1 = 0, s2 = 0;  ///< t1/p, t2/p: sinh of the ends' v
  double v1 = 0, v2 = 0;  ///< asinh(t1/p), asinh(t2/p)
  /// |v| beyond which the Yukawa pieces are negligible (infinity where they are not cut off).
  double v_stop = 0;
};

/// Radial tails of the Yukawa in-plane gradients, for d ≠ 0 (variable ρ = |d| sinh u):
///   T_SL(R) = ∫_U^∞ e^{−κ|d| cosh u}(1 + κ|d| cosh u) tanh²u du,
///   T_DL(R) = ∫_U^∞ e^{−κ|d| cosh u}(κ²d²cosh²u + 3κ|d| cosh u + 3) sinh²u / cosh⁴u du,
/// U = asinh(R/|d|). For d = 0, T_SL = E1(κR) + e^{−κR} and T_DL is not needed.
std::array<double, 2> yukawa_tails(double kappa, double abs_d, double R, double rho) {
  if (abs_d == 0.0) return {-std::expint(-kappa * R) + std::exp(-kappa * R), 0.0};
  const double U = std::asinh(R / abs_d);
  const double u_stop = std::acosh(rho / abs_d + tail_negligible_exponent / (kappa * abs_d));
  const double w0 = 1.0 / (kappa * R + std::sqrt(kappa * rho));
  double t_sl = 0.0, t_dl = 0.0;
  graded_gauss(
      tail_points_per_piece, U, u_stop, w0,
      [&](double u, double w) {
        const double ch = std::cosh(u), th = std::tanh(u);
        const double z = kappa * abs_d * ch;
        const double e = std::exp(-z);
        t_sl += w * e * (1.0 + z) * th * th;
        t_dl += w * e * (z * z + 3.0 * z + 3.0) * th * th / (ch * ch);
      },
      [](double) { return false; });
  return {t_sl, t_dl};
}

}  // namespace

PolarResolution PolarResolution::for_accuracy(double relative_accuracy) {
  // Worst error relative to the magnitude bound of n points per piece with pieces kept to
  // e^{−30}, and of dropping pieces beyond e^{−E} (about e^{−E} whatever n), measured over
  // targets up to three diameters from three panel shapes at κ·diameter 3–100 ("polar
  // resolution: measured errors", tests/bem/quadrature/test_polar_quadrature.cpp). Each is
  // taken with a factor 10 to spare.
  struct Measured {
    int points_per_piece;
    double worst;
  };
  static constexpr Measured measured[] = {{2, 2.7e-3}, {3, 1.6e-4}, {4, 1.3e-5}, {5, 1.0e-6},
                                          {6, 7.1e-8}, {7, 4.7e-9}, {8, 4.6e-10}};
  constexpr double spare = 10.0;
  const PolarResolution full;
  for (const Measured& m : measured)
    if (spare * m.worst <= relative_accuracy)
      return {m.points_per_piece,
              std::min(full.negligible_exponent, std::log(spare / relative_accuracy))};
  return full;
}

template <class Kernel>
PanelIntegrals polar_panel_integrals(const Kernel& kernel, const Panel& panel,
                                     const Eigen::Vector3d& x, bool with_gradients,
                                     const PolarResolution& resolution) {
  constexpr bool yukawa = Kernel::has_exponential_decay;
  const double kappa = kernel.kappa();
  double d = (x - panel.corners[0]).dot(panel.normal);
  // A collocation point on the panel (a centroid, say) has d at rounding level, of either sign;
  // the double layer would then jump to ±½ instead of its principal value 0.
  if (std::abs(d) <= in_plane_tolerance * panel.diameter) d = 0.0;
  const double abs_d = std::abs(d);

  std::array<Vec2, 3> P;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d r = panel.corners[static_cast<size_t>(k)] - x;
    P[static_cast<size_t>(k)] = Vec2(r.dot(panel.tangent1), r.dot(panel.tangent2));
  }
  const double tol = on_line_tolerance * panel.diameter;
  std::array<EdgeFrame, 3> edges;
  bool inside = true, outside = false;
  for (size_t e = 0; e < 3; ++e) {
    const Vec2& a = P[e];
    const Vec2& b = P[(e + 1) % 3];
    EdgeFrame& E = edges[e];
    E.u = (b - a).normalized();
    const double h = cross2(a, E.u);  // > 0 when x' is on the inner side of the edge
    E.p = std::abs(h);
    E.sigma = h > 0 ? 1.0 : -1.0;
    E.t1 = a.dot(E.u);
    E.t2 = b.dot(E.u);
    E.foot = a - E.t1 * E.u;
    if (h < -tol) outside = true;
    if (h <= tol) inside = false;
  }
  // q: in-plane distance from x' to T (0 unless x' is outside); c = distance from x to T.
  double q2 = 0.0;
  if (outside) {
    q2 = std::numeric_limits<double>::infinity();
    for (const EdgeFrame& E : edges) {
      const double tc = std::clamp(0.0, E.t1, E.t2);
      q2 = std::min(q2, E.p * E.p + tc * tc);
    }
  }
  const double c = std::sqrt(q2 + d * d);
  // Θ: the total signed angle of T seen from x' (2π inside, 0 outside, the corner angle or π
  // on the boundary).
  double theta = 0.0;
  if (inside) {
    theta = 2.0 * std::numbers::pi;
  } else if (!outside) {
    for (const EdgeFrame& E : edges)
      if (E.p > tol) theta += E.sigma * (std::atan(E.t2 / E.p) - std::atan(E.t1 / E.p));
  }
  double rho_max = 0.0;
  for (const Vec2& Pk : P) rho_max = std::max(rho_max, length2d(Pk.norm(), d));
  const bool split = yukawa && kappa * (rho_max - c) > split_exponent;
  const double exp_c = yukawa ? std::exp(-kappa * c) : 1.0;
  const double d_over_c = d == 0.0 ? 0.0 : d / c;
  // v = asinh(t/p) = sign(t)·log(|t|/p + √((t/p)² + 1)) for the six ends and, where the
  // Yukawa pieces are cut off, v_stop = acosh(r) = log(r + √(r² − 1)) for each edge, r =
  // √((c + E/κ)² − d²)/p: κδ grows with |v| away from the nearest point of the edge's line
  // and exceeds the negligible exponent E beyond |v| = v_stop. One vector logarithm for all.
  {
    using Logs = Eigen::Array<double, 16, 1>;
    Logs a = Logs::Ones();
    const double reach = split ? c + resolution.negligible_exponent / kappa : 0.0;
    const double reach_in_plane = split ? std::sqrt(std::max(0.0, reach * reach - d * d)) : 0.0;
    for (size_t e = 0; e < 3; ++e) {
      EdgeFrame& E = edges[e];
      if (E.p <= tol) continue;
      E.s1 = E.t1 / E.p;
      E.s2 = E.t2 / E.p;
      a(Eigen::Index(2 * e)) = std::abs(E.s1) + std::sqrt(E.s1 * E.s1 + 1.0);
      a(Eigen::Index(2 * e + 1)) = std::abs(E.s2) + std::sqrt(E.s2 * E.s2 + 1.0);
      if (split) {
        const double r = reach_in_plane / E.p;
        a(Eigen::Index(6 + e)) = r <= 1.0 ? 1.0 : r + std::sqrt(r * r - 1.0);
      }
    }
    const Logs l = a.log();
    for (size_t e = 0; e < 3; ++e) {
      EdgeFrame& E = edges[e];
      E.v1 = std::copysign(l(Eigen::Index(2 * e)), E.t1);
      E.v2 = std::copysign(l(Eigen::Index(2 * e + 1)), E.t2);
      E.v_stop = split ? l(Eigen::Index(6 + e)) : std::numeric_limits<double>::infinity();
    }
  }

  double sl = 0.0, dl = 0.0, g_dl_normal = 0.0;
  Vec2 g_sl = Vec2::Zero(), g_dl = Vec2::Zero();
  // ∫ e(θ) dθ over the angles the edges actually sweep. It vanishes for a closed loop, which
  // lets the in-plane gradients drop θ-independent radial constants; when x' lies on an edge
  // or at a corner that edge is skipped, the loop is open and the constants are added back.
  bool edge_skipped = false;
  Vec2 swept_direction = Vec2::Zero();

  for (const EdgeFrame& E : edges) {
    if (E.p <= tol) {
      edge_skipped = true;
      continue;
    }
    {
      // ∫_{θ1}^{θ2} (cos θ, sin θ) dθ = −J(ê2 − ê1), J the rotation by +90°.
      const Vec2 de = (E.foot + E.t2 * E.u).normalized() - (E.foot + E.t1 * E.u).normalized();
      swept_direction += Vec2(de.y(), -de.x());
    }
    const double p = E.p;
    // The in-plane gradients at one node (the values are summed over all nodes below).
    auto visit_gradients = [&](double v, double w) {
      const double ch = std::cosh(v);
      const double R = p * ch;
      const double rho = length2d(R, d);
      const double dtheta = E.sigma * w / ch;
      const double t = p * std::sinh(v);
      const Vec2 dir = (E.foot + t * E.u) / R;
      const double rho3 = rho * rho * rho;
      if constexpr (!yukawa) {
        g_sl += dtheta * (std::log(R + rho) - R / rho) * dir;
        g_dl_normal -= dtheta * R * R / rho3;
        g_dl -= dtheta * d * (rho * rho + rho * R + R * R) / ((rho + R) * rho3) * dir;
      } else {
        const auto [t_sl, t_dl] = yukawa_tails(kappa, abs_d, R, rho);
        g_sl -= dtheta * t_sl * dir;
        g_dl_normal += dtheta * std::exp(-kappa * rho) * (kappa * d * d / (rho * rho) - R * R / rho3);
        if (d != 0.0) g_dl -= dtheta * (std::copysign(1.0, d) / abs_d) * t_dl * dir;
      }
    };
    // The first piece's width at a start v_s given by sh = sinh v_s (0, t1/p or t2/p).
    auto first_width = [&](double sh) {
      if constexpr (!yukawa) {
        return max_piece_width;
      } else {
        const double ch = std::sqrt(1.0 + sh * sh);  // cosh v_s; cosh 2v_s = 2cosh² − 1
        const double rho_s = length2d(p * ch, d);
        const double a1 = kappa * p * p * std::abs(sh) * ch / rho_s;
        const double a2 = kappa * p * p * (2.0 * ch * ch - 1.0) / rho_s;
        return 1.0 / (a1 + std::sqrt(a2));
      }
    };
    auto negligible = [&](double vs) { return std::abs(vs) > E.v_stop; };
    const double v1 = E.v1, v2 = E.v2;
    const int n = resolution.points_per_piece;
    // The values, eight nodes at a time, so that the exponentials, square roots and divisions
    // use the SIMD width; the nodes wait in a buffer of whole lanes.
    constexpr int lanes = 8;
    using Lanes = Eigen::Array<double, lanes, 1>;
    constexpr int capacity = 64;
    alignas(64) std::array<double, capacity> buffer_v, buffer_w;
    int buffered = 0;
    Lanes acc_sl = Lanes::Zero(), acc_dl = Lanes::Zero();
    const auto evaluate = [&] {
      // Pad to whole lanes with weight 0 at the last node.
      for (; buffered % lanes != 0; ++buffered) {
        buffer_v[size_t(buffered)] = buffer_v[size_t(buffered - 1)];
        buffer_w[size_t(buffered)] = 0.0;
      }
      for (int begin = 0; begin < buffered; begin += lanes) {
        const Lanes v = Eigen::Map<const Lanes, Eigen::Aligned64>(buffer_v.data() + begin);
        const Lanes w = Eigen::Map<const Lanes, Eigen::Aligned64>(buffer_w.data() + begin);
        const Lanes ev = linalg::vector_exp<Lanes>(v);
        const Lanes ch = 0.5 * (ev + ev.inverse());  // cosh v
        const Lanes R = p * ch;
        const Lanes rho = (R.square() + d * d).sqrt();
        const Lanes dtheta = (E.sigma * w) / ch;
        if constexpr (yukawa) {
          if (split) {
            // e^{−κρ'} directly: the rounding of ρ' − c is far below 1/κ.
            const Lanes e = linalg::vector_exp<Lanes>(-kappa * rho) * dtheta;
            acc_sl += e;
            acc_dl += e / rho;
            continue;
          }
        }
        // δ = ρ' − c without cancellation (ρ'² − c² = R² − q²).
        const Lanes delta = (R.square() - q2) / (rho + c);
        if constexpr (!yukawa) {
          acc_sl += dtheta * delta;
          acc_dl += d_over_c * (dtheta * delta / rho);
        } else {
          const Lanes em = -(-kappa * delta).expm1();
          acc_sl += exp_c / kappa * (dtheta * em);
          acc_dl += d_over_c * exp_c * (dtheta * (delta + c * em) / rho);
        }
      }
      buffered = 0;
    };
    const auto visit = [&](double v, double w) {
      if (with_gradients) visit_gradients(v, w);
      buffer_v[size_t(buffered)] = v;
      buffer_w[size_t(buffered)] = w;
      if (++buffered == capacity) evaluate();
    };
    const auto walk = [&](double start, double end, double sinh_start) {
      graded_gauss(n, start, end, first_width(sinh_start), visit, negligible);
    };
    if (v1 < 0.0 && v2 > 0.0) {
      walk(0.0, v2, 0.0);
      walk(0.0, v1, 0.0);
    } else if (v1 >= 0.0) {
      walk(v1, v2, E.s1);
    } else {
      walk(v2, v1, E.s2);
    }
    if (buffered > 0) evaluate();
    if (yukawa && split) {
      sl -= acc_sl.sum() / kappa;
      dl -= d * acc_dl.sum();
    } else {
      sl += acc_sl.sum();
      dl += acc_dl.sum();
    }
  }
  if constexpr (yukawa) {
    if (split) {
      sl += exp_c * theta / kappa;
      dl += d_over_c * exp_c * theta;
    }
    if (with_gradients) g_dl_normal -= kappa * std::exp(-kappa * abs_d) * theta;
  }
  if (with_gradients && edge_skipped && d != 0.0) {
    // The dropped constants: −log|d| (Laplace SL), 1/d (Laplace DL), the full radial
    // integrals I∞ = T(R = 0) (Yukawa SL and DL).
    if constexpr (!yukawa) {
      g_sl -= std::log(abs_d) * swept_direction;
      g_dl += swept_direction / d;
    } else {
      const auto [i_sl, i_dl] = yukawa_tails(kappa, abs_d, 0.0, abs_d);
      g_sl += i_sl * swept_direction;
      g_dl += (std::copysign(1.0, d) / abs_d) * i_dl * swept_direction;
    }
  }

  constexpr double inv_four_pi = 0.25 * std::numbers::inv_pi;
  PanelIntegrals result;
  result.single_layer = inv_four_pi * sl;
  result.double_layer = inv_four_pi * dl;
  if (with_gradients) {
    const Eigen::Vector3d sl_plane = g_sl.x() * panel.tangent1 + g_sl.y() * panel.tangent2;
    const Eigen::Vector3d dl_plane = g_dl.x() * panel.tangent1 + g_dl.y() * panel.tangent2;
    // n·∇_x single layer = ∫ G'(r) d/r dA = −double layer.
    result.single_layer_gradient = inv_four_pi * sl_plane - result.double_layer * panel.normal;
    result.double_layer_gradient = inv_four_pi * (dl_plane + g_dl_normal * panel.normal);
  }
  return result;
}

template PanelIntegrals polar_panel_integrals<LaplaceKernel>(const LaplaceKernel&, const Panel&,
                                                             const Eigen::Vector3d&, bool,
                                                             const PolarResolution&);
template PanelIntegrals polar_panel_integrals<YukawaKernel>(const YukawaKernel&, const Panel&,
                                                            const Eigen::Vector3d&, bool,
                                                            const PolarResolution&);

}  // namespace bemshape::bem
