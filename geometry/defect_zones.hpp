#pragma once
// Where a prepared surface is not the boundary of a solid: regions where it crosses itself
// and no solid could be recovered (surface_repair.hpp). The analysis measures on the surface
// as given there, and every output marks the faces near such a region `defect`, so that a
// verdict says what it rests on (docs/geometry.md, "What is measured around").

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

struct DefectZone {
  /// What is wrong there, e.g. "the surface crosses itself".
  std::string what;
  /// Why it was not repaired, e.g. "the surface is inside out over a region of volume 0.02
  /// (winding number −1 there), so the solid it bounds cannot be told".
  std::string why;
  /// Bounding box of the region: of the curves where the surface crosses itself, and of the
  /// pieces of surface around which the winding number is other than 0 or 1 where that is
  /// known [model units].
  BoundingBox box;
  /// Intersecting face pairs in the region.
  std::size_t pairs = 0;

  Eigen::Vector3d centre() const { return 0.5 * (box.min + box.max); }
  /// Bounding-box diagonal [model units].
  double size() const { return box.diagonal(); }
};

/// flags[f] = 1 for every face of `mesh` whose bounding box comes within `margin` [model
/// units] of some zone's box (max-norm distance between the boxes), else 0. The analysis
/// passes h0: the thickness beyond one h0 from a zone is what the rest of the part reads.
std::vector<char> faces_near_defects(const SurfaceMesh& mesh, const std::vector<DefectZone>& zones,
                                     double margin);

}  // namespace bemshape::geometry
