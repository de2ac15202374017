#pragma once
// Internal: CGAL's autorefinement of a surface that crosses itself, and the exact
// predicates the winding-number labelling of its pieces needs (winding_number_boundary.cpp),
// behind plain Eigen types so that CGAL is compiled in one translation unit
// (cgal_autorefinement.cpp) and never appears in a header.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace bemshape::geometry::detail {

struct CgalAutorefinement {
  /// The refined surface [model units]: every face of the input split along the curves where
  /// it meets other faces, so that no two faces cross; the points of the curves are exact
  /// intersections rounded to double. The pieces of the different sheets along a curve have
  /// their own copies of its vertices (equal coordinates).
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  /// source[f]: the input face that output face f is a piece of.
  std::vector<Eigen::Index> source;
  bool ok = false;
  /// Why the refinement failed (ok == false): CGAL's message.
  std::string failure;
};

/// CGAL::Polygon_mesh_processing::experimental::autorefine of a closed, consistently
/// oriented triangle mesh with at most two faces per edge and one fan per vertex. CGAL 5.5's
/// autorefinement leaves some degenerate configurations (e.g. three faces meeting along a
/// segment) to assertions; its translation unit is compiled with CGAL's assertions on
/// (CGAL_DEBUG), so that such a case throws and comes back as ok == false with the reason,
/// instead of reading past an array. Throws CancelledError if the run is cancelled.
CgalAutorefinement cgal_autorefine(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

/// Exact sign (+1, 0, −1) of det[b − a, c − a, d − a]: +1 if d lies on the side of the plane
/// through a, b, c that the normal (b − a)×(c − a) points to (CGAL::orientation).
int exact_orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d);

/// For coplanar p, q, r, s: +1 if s lies on the same side of the line pq as r, −1 on the
/// other side, 0 on the line (CGAL::coplanar_orientation, exact).
int exact_coplanar_orientation(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                               const Eigen::Vector3d& r, const Eigen::Vector3d& s);

}  // namespace bemshape::geometry::detail
