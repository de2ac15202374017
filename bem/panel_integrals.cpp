#include "bem/panel_integrals.hpp"

#include <limits>

namespace bemshape::bem {

const std::array<FarFieldRule, 8>& far_field_rules() {
  constexpr double any = std::numeric_limits<double>::infinity();
  static const std::array<FarFieldRule, 8> table = {{
      {40.0, 0.5, &symmetric_triangle_rule(1)},
      {20.0, 0.5, &symmetric_triangle_rule(2)},
      {10.0, 1.0, &symmetric_triangle_rule(4)},
      {8.0, 1.0, &symmetric_triangle_rule(5)},
      {6.0, 1.5, &symmetric_triangle_rule(6)},
      {4.0, 2.0, &symmetric_triangle_rule(8)},
      {3.0, 3.0, &collapsed_gauss_rule(8)},
      {2.0, 3.0, &collapsed_gauss_rule(12)},
  }};
  (void)any;
  return table;
}

}  // namespace bemshape::bem
