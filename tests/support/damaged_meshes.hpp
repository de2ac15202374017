#pragma once
// Damaged meshes made by code, each with the intact part it was made from and the outcome
// bemshape must give: surfaces that cross themselves the way real exports do (a bar whose
// end passes through itself, a link crossing itself, two bodies overlapping with shared
// faces, a strip folded over its neighbours, a patch of a wall pushed through the opposite
// wall, a block with a few dozen crossing face pairs). The corpus of tests/geometry and
// tests/apps, and of `make_test_mesh damaged NAME`.
//
// Lengths in model units (the parts are a few units across, like the bundled unit sphere).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::testing {

/// A bar of rectangular section swept along a path: at each path point the section (width
/// across the path, horizontal; height vertical, both centred on the point) stands
/// perpendicular to the path's direction there (central differences). A closed path gives a
/// tube without caps, an open one a bar with flat end caps. Oriented so that its signed
/// volume is positive; where the path passes through the bar itself, the surface crosses
/// itself. The path must not run vertically.
geometry::SurfaceMesh swept_bar(const std::vector<Eigen::Vector3d>& path, bool closed, double width,
                                double height);

/// The part of that bar from path point `first` to `last` (indices modulo the path's length
/// for a closed path), with end caps; its sections are those of the whole bar.
geometry::SurfaceMesh swept_bar_part(const std::vector<Eigen::Vector3d>& path, bool closed,
                                     double width, double height, int first, int last);

/// `mesh` with every edge longer than `edge` that passes within `radius` of `site` split at
/// its midpoint, until none is left (faces with one, two or three such edges split into two,
/// three or four): the same surface, finer around the site.
geometry::SurfaceMesh refined_near(const geometry::SurfaceMesh& mesh, const Eigen::Vector3d& site,
                                   double radius, double edge);

/// `mesh` with the patch of its surface within `radius` of `site` on the skin whose outward
/// normal is `normal` there pushed inward, through the wall of thickness `wall` behind it, to
/// `overshoot` beyond the opposite skin at the centre: each vertex x of the skin within the
/// radius moves by −(wall + overshoot)·(1 − (|x − site|/radius)²)·n(x), n the skin's normal
/// (`normal` on a flat skin, the radial direction from `centre` on a sphere if `spherical`).
/// The faces keep their vertices, so the surface crosses itself where the patch passes the
/// opposite skin.
geometry::SurfaceMesh pushed_through(const geometry::SurfaceMesh& mesh, const Eigen::Vector3d& site,
                                     const Eigen::Vector3d& normal, double radius, double wall,
                                     double overshoot, bool spherical = false,
                                     const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

/// What bemshape must do with a damaged mesh.
enum class DamageOutcome {
  /// Split along the curves where it crosses itself and replaced by the boundary of the
  /// region it encloses (sheets overlap: the intended solid is clear).
  resolved,
  /// Bodies united (crossing shells).
  united,
  /// A crossing within the repair length cut out and refilled, a solid recovered (a tip
  /// pushed through the opposite wall may stay as a small shell of its own).
  refilled,
  /// Measured on the surface as given, the crossing region reported and marked `defect`.
  measured_around
};

/// "resolved", "united", "refilled", "measured around".
const char* to_string(DamageOutcome outcome);

struct DamagedMesh {
  std::string name;
  std::string description;
  /// The damaged surface as a file would hold it (any orientation, shells as made).
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  /// The part before the damage (closed, outward), for comparing thicknesses away from it.
  geometry::SurfaceMesh intact;
  /// Whether a solid recovered must be `intact` itself (volume and area to rounding): false
  /// where the damage changed the shape around it (a fold).
  bool exact_intact = true;
  /// Centre and size (bounding-box diagonal) of the damaged region [model units].
  Eigen::Vector3d site = Eigen::Vector3d::Zero();
  double size = 0.0;
  DamageOutcome outcome = DamageOutcome::resolved;
  /// The wall thickness of the part away from the damage, and an h0 and solver edge that
  /// resolve it on a small mesh (the end-to-end tests).
  double wall = 0.0;
  double h0 = 0.0;
  double max_edge = 0.0;
};

/// The corpus, in a fixed order.
std::vector<DamagedMesh> damaged_meshes();

/// The corpus entry called `name`; throws std::invalid_argument naming the choices.
DamagedMesh damaged_mesh(const std::string& name);

}  // namespace bemshape::testing
