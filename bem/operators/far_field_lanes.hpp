#pragma once
// Galerkin entries of well-separated panel pairs, kFarFieldLanes pairs at once: the Laplace
// far field, and the Yukawa pairs whose attenuation allows a low-order rule (at the end).
//
// For a pair (T_j, T_k) whose centroids are at least OuterRuleThresholds::far_ratio of the
// larger diameter apart, GalerkinOperators::entry takes the test centroid x = c_j as the
// outer rule and a Gauss rule (w_q, ξ_q, η_q) on T_k chosen by |x − c_k|/diam T_k
// (bem/quadrature/panel_integrals.hpp):
//
//   V[j, k] = |T_j||T_k|/(4π) Σ_q w_q / r_q,
//   K[j, k] = |T_j||T_k|/(4π) d Σ_q w_q / r_q³,
//
// r_q = |x − a_k − ξ_q e1_k − η_q e2_k|, d = (x − a_k)·n_k. Those Gauss rules have 3 to 16
// points, and one pair at a time spends its time on the latency of one square root after
// another. Here the same sums run across kFarFieldLanes pairs in SIMD registers: the pairs of
// one row of an operator block (one test panel, consecutive trial panels) or of one column.
// `laplace_far_field_lanes` says which lanes it computed; the caller takes the near pairs one
// at a time. Same rules, same formulas: the results differ from `entry` only by rounding.

#include <array>
#include <cstddef>
#include <span>

#include <Eigen/Core>

#include "bem/kernels/laplace_kernel.hpp"
#include "bem/operators/panel_arrays.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/quadrature/triangle_quadrature.hpp"
#include "bem/kernels/yukawa_kernel.hpp"

namespace bemshape::bem {

/// Pairs per SIMD pass: 8 doubles fill one AVX-512 register or two AVX2 ones.
inline constexpr int kFarFieldLanes = 8;
using FarFieldLanes = Eigen::Array<double, kFarFieldLanes, 1>;

/// The geometry of kFarFieldLanes panels as lanes: consecutive panels of a PanelArrays, one
/// panel in every lane, or any kFarFieldLanes panels.
struct PanelLanes {
  std::array<FarFieldLanes, 3> centroid, corner, edge1, edge2, normal;
  FarFieldLanes area, diameter;

  /// Panels first … first + kFarFieldLanes − 1.
  static PanelLanes consecutive(const PanelArrays& arrays, Eigen::Index first) {
    return load([&](PanelArrays::Field f) {
      return FarFieldLanes(Eigen::Map<const FarFieldLanes>(arrays.column(f) + first));
    });
  }

  /// Panel i in every lane.
  static PanelLanes repeated(const PanelArrays& arrays, Eigen::Index i) {
    return load([&](PanelArrays::Field f) {
      return FarFieldLanes(FarFieldLanes::Constant(arrays.column(f)[i]));
    });
  }

  /// Panels panels[0] … panels[kFarFieldLanes − 1], in any order.
  static PanelLanes gathered(const PanelArrays& arrays,
                             const std::array<Eigen::Index, kFarFieldLanes>& panels) {
    return load([&](PanelArrays::Field f) {
      const double* column = arrays.column(f);
      FarFieldLanes values;
      for (int l = 0; l < kFarFieldLanes; ++l) values(l) = column[panels[static_cast<std::size_t>(l)]];
      return values;
    });
  }

 private:
  /// Every field, from lanes(field).
  template <class Lanes>
  static PanelLanes load(const Lanes& lanes) {
    PanelLanes p;
    for (int c = 0; c < 3; ++c) {
      const auto s = static_cast<std::size_t>(c);
      p.centroid[s] = lanes(PanelArrays::Field(PanelArrays::centroid_x + c));
      p.corner[s] = lanes(PanelArrays::Field(PanelArrays::corner_x + c));
      p.edge1[s] = lanes(PanelArrays::Field(PanelArrays::edge1_x + c));
      p.edge2[s] = lanes(PanelArrays::Field(PanelArrays::edge2_x + c));
      p.normal[s] = lanes(PanelArrays::Field(PanelArrays::normal_x + c));
    }
    p.area = lanes(PanelArrays::area);
    p.diameter = lanes(PanelArrays::diameter);
    return p;
  }
};

/// V and K of the pairs (test lane l, trial lane l).
struct FarFieldEntries {
  FarFieldLanes single_layer, double_layer;
};

/// V = |T_j||T_k|/(4π) Σ_q w_q g(r_q) and K = |T_j||T_k|/(4π) d Σ_q w_q h(r_q) of the pairs by
/// `rule` on the trial panels, in every lane, with the kernel's g = E(r)/r and
/// h = E(r)(1 + κr)/r³ (E = 1 for Laplace, e^{−κr} for Yukawa; radial_kernel_terms).
template <class Kernel>
FarFieldEntries far_field_sums(const PanelLanes& test, const PanelLanes& trial,
                               const TriangleRule& rule, const Kernel& kernel) {
  // x − a_k and d = (x − a_k)·n_k per lane.
  const FarFieldLanes ox = test.centroid[0] - trial.corner[0];
  const FarFieldLanes oy = test.centroid[1] - trial.corner[1];
  const FarFieldLanes oz = test.centroid[2] - trial.corner[2];
  const FarFieldLanes d = ox * trial.normal[0] + oy * trial.normal[1] + oz * trial.normal[2];
  FarFieldLanes sum_g = FarFieldLanes::Zero(), sum_h = FarFieldLanes::Zero(), g, h;
  for (int q = 0; q < rule.size(); ++q) {
    const auto k = static_cast<std::size_t>(q);
    const double xi = rule.xi[k], eta = rule.eta[k], w = rule.weight[k];
    const FarFieldLanes rx = ox - xi * trial.edge1[0] - eta * trial.edge2[0];
    const FarFieldLanes ry = oy - xi * trial.edge1[1] - eta * trial.edge2[1];
    const FarFieldLanes rz = oz - xi * trial.edge1[2] - eta * trial.edge2[2];
    radial_kernel_terms(kernel, FarFieldLanes(rx.square() + ry.square() + rz.square()), g, h);
    sum_g += w * g;
    sum_h += w * h;
  }
  const FarFieldLanes scale = Kernel::inv_four_pi * test.area * trial.area;
  return {scale * sum_g, scale * d * sum_h};
}

/// The Laplace far-field entries of the pairs by `rule`, in every lane.
inline FarFieldEntries laplace_far_field_rule(const PanelLanes& test, const PanelLanes& trial,
                                              const TriangleRule& rule) {
  return far_field_sums(test, trial, rule, LaplaceKernel{});
}

/// The Laplace far-field entries of the kFarFieldLanes pairs, for the pairs at least
/// `far_ratio` times the larger diameter apart (the caller passes
/// OuterRuleThresholds::far_ratio; closer pairs need GalerkinOperators::entry's outer rules).
/// Returns the lanes computed as a bit mask (bit l for lane l). Each lane gets the rule
/// integrate_panel selects for it from `rows` (far_field_rules() or its single-precision
/// table: the first row it qualifies for, on squared distances as
/// select_far_field_rule_squared, κ·diameter = 0): one SIMD pass per distinct rule among the
/// lanes, usually one, two where a row of trial panels crosses a threshold.
inline unsigned laplace_far_field_lanes(const PanelLanes& test, const PanelLanes& trial,
                                        double far_ratio, FarFieldEntries& out,
                                        std::span<const FarFieldRule> rows = far_field_rules()) {
  const FarFieldLanes dx = test.centroid[0] - trial.centroid[0];
  const FarFieldLanes dy = test.centroid[1] - trial.centroid[1];
  const FarFieldLanes dz = test.centroid[2] - trial.centroid[2];
  const FarFieldLanes distance2 = dx.square() + dy.square() + dz.square();
  const FarFieldLanes trial_diameter2 = trial.diameter.square();
  // Row index per lane, −1 where no row applies or the pair is not in the far field.
  FarFieldLanes row = FarFieldLanes::Constant(-1.0);
  for (int r = static_cast<int>(rows.size()) - 1; r >= 0; --r)
    row = (distance2 >= rows[static_cast<std::size_t>(r)].min_ratio_squared() * trial_diameter2)
              .select(FarFieldLanes::Constant(r), row);
  const auto far = distance2 >= far_ratio * far_ratio * test.diameter.max(trial.diameter).square();
  row = far.select(row, FarFieldLanes::Constant(-1.0));
  unsigned done = 0;
  for (int r = 0; r < static_cast<int>(rows.size()); ++r) {
    const auto lanes = row == double(r);
    if (!lanes.any()) continue;
    const FarFieldEntries e = laplace_far_field_rule(test, trial, *rows[static_cast<std::size_t>(r)].rule);
    out.single_layer = lanes.select(e.single_layer, out.single_layer);
    out.double_layer = lanes.select(e.double_layer, out.double_layer);
    for (int l = 0; l < kFarFieldLanes; ++l)
      if (lanes(l)) done |= 1u << l;
  }
  return done;
}

/// The Yukawa entries of attenuated pairs (GalerkinOperators::attenuated_entry: the test
/// centroid x against the trial panel's collapsed Gauss `rule`), in every lane:
///   V = |T_j||T_k|/(4π) Σ_q w_q e^{−κr_q}/r_q,
///   K = |T_j||T_k|/(4π) d Σ_q w_q e^{−κr_q}(1 + κr_q)/r_q³,
/// r_q and d as for the Laplace far field above. κ [1/model units].
inline FarFieldEntries yukawa_attenuated_lanes(const PanelLanes& test, const PanelLanes& trial,
                                               double kappa, const TriangleRule& rule) {
  return far_field_sums(test, trial, rule, YukawaKernel{kappa});
}

}  // namespace bemshape::bem
