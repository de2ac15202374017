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
//
// The check (thin_check): every face below the threshold counts towards the verdict; regions
// smaller than the speck area are set aside from the list of regions, never from the verdict.

#include <cstddef>
#include <limits>
#include <optional>
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

/// Whether face f's reading counts (the measurable faces above): below `unmeasurable_from`
/// and of positive area.
inline bool measurable_face(const geometry::SurfaceMesh& mesh, const Eigen::VectorXd& thickness,
                            Eigen::Index f, double unmeasurable_from) {
  return thickness(f) < unmeasurable_from && mesh.face_areas()(f) > 0.0;
}

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

/// Default speck area, in units of h0²: a quarter of a square of side h0, below any feature a
/// part is designed with at that h0 and above the few solver faces where three walls meet and
/// the reading dips (docs/theory.md, "Wall thickness").
inline constexpr double kSpeckArea = 0.25;

/// The speck area never exceeds this fraction of the part's surface area: h0²/4 means a speck
/// only while h0 is small against the part (area ≥ 250·h0²). When h0 is comparable to the part
/// — a small part, or a limit given in millimetres for a file in metres — h0²/4 can exceed
/// the whole surface, and a thin part would be set aside whole (docs/usage.md, "The check").
inline constexpr double kSpeckPartFraction = 1e-3;

/// The speck area [model units²]: `requested` (≥ 0; --min-region-area) or kSpeckArea·h0²,
/// and never more than kSpeckPartFraction·part_area (part_area: the surface's area).
double speck_area(std::optional<double> requested, double h0, double part_area);

/// The verdict of a minimum-wall-thickness check and the specks it set aside from the list of
/// regions (docs/usage.md, "The check"). Every face thinner than the threshold counts: the
/// check fails when their area reaches the speck area, and whenever any face is thin with a
/// speck area of 0. A PASS therefore means that the faces below the limit cover less than the
/// speck area in all, at most kSpeckPartFraction of the part.
struct ThinCheck {
  double speck_area = 0.0;  ///< regions smaller than it are specks [model units²]
  double thin_area = 0.0;   ///< area of every face thinner than the threshold [model units²]
  double speck_total = 0.0;  ///< area of the specks [model units²]
  /// Regions smaller than speck_area, most severe first: not among the regions listed, but
  /// reported with them (where, how thin, how large).
  std::vector<ThinRegion> specks;
  bool pass = true;  ///< thin_area = 0, or 0 < thin_area < speck_area
  /// No face was measurable at h0 and the run was asked to fail the check rather than refuse
  /// (ThicknessOptions::unmeasurable_fails_check): pass is false, thin_area 0.
  bool unmeasurable = false;
};

/// The check of `regions` (every thin region of thin_regions: together they hold every thin
/// face) against `speck_area`: moves the regions smaller than speck_area out of `regions` into
/// the result's specks, keeping both in order of severity.
ThinCheck thin_check(std::vector<ThinRegion>& regions, double speck_area);

}  // namespace bemshape::analysis
