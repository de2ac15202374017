#pragma once
// Orientation repair. A solid's boundary is oriented when (1) neighbouring faces traverse
// their shared edge in opposite directions, and (2) every shell bounds the solid: the normal
// points away from the material. For nested shells this is the rule of CGAL's
// Polygon_mesh_processing::orient_to_bound_a_volume: a shell inside an even number of other
// shells (0: an outer skin, 2: an island inside a cavity) encloses positive volume, a shell
// inside an odd number (a cavity wall) encloses negative volume, normals into the cavity.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace bemshape::geometry {

struct ConsistentOrientation {
  /// #F×3 faces, some reversed.
  Eigen::MatrixX3i faces;
  /// Faces reversed so that neighbours agree (the smaller side of each shell is flipped).
  std::size_t faces_flipped = 0;
  /// False if some shell cannot be oriented (a Möbius-like band); faces is then unchanged in
  /// that shell.
  bool orientable = true;
  /// A point of the first non-orientable shell [model units].
  Eigen::Vector3d non_orientable_at = Eigen::Vector3d::Zero();
};

/// Makes neighbouring faces agree across every edge shared by exactly two faces (edges with
/// one or ≥ 3 faces are left alone: validation refuses those meshes).
ConsistentOrientation orient_consistently(const Eigen::MatrixX3d& vertices,
                                          const Eigen::MatrixX3i& faces);

/// One shell of a closed mesh after outward orientation.
struct ShellOrientation {
  std::size_t faces = 0;
  /// Signed volume after orientation [model units³]: > 0 outer skins, < 0 cavities.
  double volume = 0.0;
  /// Number of other shells containing this one.
  int depth = 0;
  /// True if the shell was inside-out and has been reversed.
  bool flipped = false;
  /// A point on the shell (centroid of its largest face) [model units].
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
};

struct VolumeOrientation {
  Eigen::MatrixX3i faces;
  std::vector<ShellOrientation> shells;
  std::size_t shells_flipped = 0;
  std::size_t faces_flipped = 0;
  /// Shells with odd depth: the walls of cavities.
  std::size_t cavities = 0;
};

/// Reverses whole shells so that each bounds the solid (rule above). Requires a closed,
/// consistently oriented mesh without self-intersections: nesting is decided by the
/// winding number of one point of each shell with respect to every other shell.
VolumeOrientation orient_to_bound_volume(const Eigen::MatrixX3d& vertices,
                                         const Eigen::MatrixX3i& faces);

}  // namespace bemshape::geometry
