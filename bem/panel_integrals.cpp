#include "bem/panel_integrals.hpp"

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

}  // namespace bemshape::bem
