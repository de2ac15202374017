#pragma once
// Area-weighted statistics of a per-face thickness on a surface, and the thin regions of a
// minimum-wall-thickness check.
//
//   thickness: #F per-face values [model units]; faces whose value is at or above
//              `unmeasurable_from` (features' saturation value kMaxThicknessFactor·h0: far
//              from any opposite wall, see features/thickness.hpp) are left out of the
//              statistics and counted in unmeasurable_area.
//
// Quantiles are of the area distribution: p05 is the thickness below which 5 % of the
// (measurable) area lies. Each face stands for its area spread at its value, and the
// quantile is interpolated linearly between the faces' area midpoints.
//
// A thin region is a set of faces with thickness < threshold connected through shared
// edges. Regions are sorted by severity: thinnest minimum first, larger area first on ties.

#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::analysis {

struct ThicknessStatistics {
  double minimum = 0, maximum = 0, mean = 0, median = 0, p05 = 0, p95 = 0;  // [model units]
  Eigen::Vector3d min_location = Eigen::Vector3d::Zero();  ///< centroid of the thinnest face
  double measured_area = 0.0;                              ///< [model units²]
  double unmeasurable_area = 0.0;                          ///< [model units²]
};

/// Throws InputError if no face is measurable (no wall opposes any face at this h0).
ThicknessStatistics thickness_statistics(const geometry::SurfaceMesh& mesh,
                                         const Eigen::VectorXd& thickness,
                                         double unmeasurable_from);

/// Area-weighted p-quantile, p ∈ [0, 1], of `values` with weights `areas` (both #F, areas > 0
/// somewhere); see above.
double weighted_quantile(const Eigen::VectorXd& values, const Eigen::VectorXd& areas, double p);

struct ThinRegion {
  std::size_t faces = 0;
  double area = 0.0;                                       ///< [model units²]
  double minimum = 0.0;                                    ///< thinnest face value [model units]
  Eigen::Vector3d min_location = Eigen::Vector3d::Zero();  ///< centroid of the thinnest face
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();      ///< area-weighted centroid
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero();       ///< bounding box of its faces
  Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
  std::vector<int> face_indices;                           ///< the `faces` faces, ascending
  int extreme_face = -1;                                   ///< the thinnest face
};

/// A thick region: an edge-connected set of measurable faces thicker than a threshold (a
/// mass of material a designer may want to core out), thickest first.
struct ThickRegion {
  std::size_t faces = 0;
  double area = 0.0;                                       ///< [model units²]
  double maximum = 0.0;                                    ///< thickest face value [model units]
  Eigen::Vector3d max_location = Eigen::Vector3d::Zero();  ///< centroid of the thickest face
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();      ///< area-weighted centroid
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero();       ///< bounding box of its faces
  Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
  std::vector<int> face_indices;                           ///< the `faces` faces, ascending
  int extreme_face = -1;                                   ///< the thickest face
  /// Where the thickest face's wall has its middle (the skeleton point its thickness was read
  /// at), NaN when the measure has none (analysis/wall_thickness.hpp) [model units].
  Eigen::Vector3d skeleton_point = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// Every edge-connected set of faces with thickness < threshold, most severe first. With
/// `across` (#F: the face across the wall, −1 for none; analysis/wall_thickness.hpp), a face
/// and the face across its wall join one region when both are selected: the two skins of a
/// thin wall are one feature even where no thin face joins them by an edge (a pocket's
/// ceiling and the floor above it).
std::vector<ThinRegion> thin_regions(const geometry::SurfaceMesh& mesh,
                                     const Eigen::VectorXd& thickness, double threshold,
                                     const Eigen::VectorXi& across = {});

/// Every edge-connected set of faces with unmeasurable_from > thickness > threshold, thickest
/// first (faces at the saturation value, far from any opposite wall, are not thick walls);
/// `across` as for thin_regions.
std::vector<ThickRegion> thick_regions(const geometry::SurfaceMesh& mesh,
                                       const Eigen::VectorXd& thickness, double threshold,
                                       double unmeasurable_from,
                                       const Eigen::VectorXi& across = {});

}  // namespace bemshape::analysis
