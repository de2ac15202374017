#pragma once
// The panel geometry the far-field Gauss rules read (bem/operators/far_field_lanes.hpp), as a structure
// of arrays: one contiguous column per quantity, so that consecutive panels load straight
// into SIMD lanes. Same values as the Panel structs, in the same order.

#include <vector>

#include <Eigen/Core>

#include "bem/quadrature/panel.hpp"

namespace bemshape::bem {

class PanelArrays {
 public:
  enum Field {
    centroid_x, centroid_y, centroid_z,  ///< (a + b + c)/3
    corner_x, corner_y, corner_z,        ///< a
    edge1_x, edge1_y, edge1_z,           ///< b − a
    edge2_x, edge2_y, edge2_z,           ///< c − a
    normal_x, normal_y, normal_z,        ///< unit normal n
    area,                                ///< |T|
    diameter,                            ///< longest edge
    field_count
  };

  explicit PanelArrays(const std::vector<Panel>& panels)
      : values_(static_cast<Eigen::Index>(panels.size()), field_count) {
    for (Eigen::Index i = 0; i < values_.rows(); ++i) {
      const Panel& p = panels[static_cast<std::size_t>(i)];
      for (int c = 0; c < 3; ++c) {
        values_(i, centroid_x + c) = p.centroid[c];
        values_(i, corner_x + c) = p.corners[0][c];
        values_(i, edge1_x + c) = p.edge1[c];
        values_(i, edge2_x + c) = p.edge2[c];
        values_(i, normal_x + c) = p.normal[c];
      }
      values_(i, area) = p.area;
      values_(i, diameter) = p.diameter;
    }
  }

  Eigen::Index size() const { return values_.rows(); }
  /// The values of field f for panels 0 … size() − 1, contiguous.
  const double* column(Field f) const { return values_.col(f).data(); }

 private:
  Eigen::Matrix<double, Eigen::Dynamic, field_count> values_;  // column-major
};

}  // namespace bemshape::bem
