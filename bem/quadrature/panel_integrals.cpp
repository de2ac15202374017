#include "bem/quadrature/panel_integrals.hpp"

namespace bemshape::bem {

const std::array<FarFieldRule, 7>& far_field_rules() {
  // Measured worst errors (relative to the entry's natural magnitude area·|G^{(k)}(r)|) over
  // equilateral, right and obtuse panels and 43 directions per ratio, docs/quadrature.md:
  // each row keeps the error below ~2e−9 in its whole range.
  static const std::array<FarFieldRule, 7> table = {{
      {150.0, 0.01, &symmetric_triangle_rule(2)},  // 3 points
      {12.0, 0.3, &symmetric_triangle_rule(5)},    // 7 points
      {6.0, 0.7, &symmetric_triangle_rule(6)},     // 12 points
      {4.0, 1.0, &symmetric_triangle_rule(8)},     // 16 points
      {8.0, 1.5, &symmetric_triangle_rule(8)},
      {2.5, 2.5, &collapsed_gauss_rule(6)},  // 36 points
      {1.5, 5.0, &collapsed_gauss_rule(8)},  // 64 points
  }};
  return table;
}

const std::array<FarFieldRule, 5>& single_precision_far_field_rules() {
  // Measured worst errors at each row's smallest ratio (the calibration of far_field_rules(),
  // values and gradients, three panel shapes, 43 directions; docs/quadrature.md): 7.5e−8,
  // 4.8e−8, 4.2e−9, 2.6e−8 and 4.9e−8.
  static const std::array<FarFieldRule, 5> table = {{
      {60.0, 0.0, &symmetric_triangle_rule(2)},  // 3 points
      {6.0, 0.0, &symmetric_triangle_rule(5)},   // 7 points
      {4.0, 0.0, &symmetric_triangle_rule(6)},   // 12 points
      {2.5, 0.0, &symmetric_triangle_rule(8)},   // 16 points
      {1.5, 0.0, &collapsed_gauss_rule(6)},      // 36 points
  }};
  return table;
}

std::span<const FarFieldRule> far_field_rules(double accuracy) {
  if (accuracy >= kSinglePrecisionRuleAccuracy) return single_precision_far_field_rules();
  return far_field_rules();
}

const std::array<AttenuatedRule, 7>& attenuated_far_field_rules() {
  // Measured worst errors of V and K relative to area/(4πr) and area/(4πr²) over equilateral,
  // right and obtuse panels and 43 directions, at κ·diameter 1, 1.5, 2, 2.5, 3, 3.5, 4, 5, 6
  // and 8 and ratios 1.5, 2, 2.5, 3, 4 and 6 (docs/quadrature.md): each row stays below
  // 2e−10, a fifth of kAttenuatedRuleAccuracy, at every measured point of its window, and
  // the errors fall monotonically with the ratio and vary smoothly with κ·diameter.
  static const std::array<AttenuatedRule, 7> table = {{
      {4.0, 2.5, 8.0, &symmetric_triangle_rule(6)},  // 12 points
      {3.0, 5.0, 8.0, &symmetric_triangle_rule(6)},
      {4.0, 1.0, 8.0, &symmetric_triangle_rule(8)},  // 16 points
      {3.0, 3.0, 8.0, &symmetric_triangle_rule(8)},
      {3.0, 1.5, 3.0, &collapsed_gauss_rule(5)},  // 25 points
      {2.0, 1.0, 8.0, &collapsed_gauss_rule(6)},  // 36 points
      {1.5, 1.0, 8.0, &collapsed_gauss_rule(7)},  // 49 points
  }};
  return table;
}

const std::array<AttenuatedRule, 3>& single_precision_attenuated_rules() {
  // Measured worst errors at each row's smallest ratio on the scale of the table above (the
  // calibration "attenuated Yukawa rules: measured errors …", κ·diameter 1–8): 2.5e−8,
  // 3.1e−8 and 5.0e−9, within kSinglePrecisionRuleAccuracy.
  static const std::array<AttenuatedRule, 3> table = {{
      {2.5, 1.0, 8.0, &symmetric_triangle_rule(6)},  // 12 points
      {2.0, 1.0, 8.0, &symmetric_triangle_rule(8)},  // 16 points
      {1.5, 1.0, 8.0, &collapsed_gauss_rule(6)},     // 36 points
  }};
  return table;
}

std::span<const AttenuatedRule> attenuated_rules(double accuracy) {
  if (accuracy >= kSinglePrecisionRuleAccuracy) return single_precision_attenuated_rules();
  return attenuated_far_field_rules();
}

}  // namespace bemshape::bem
