#include "geometry/defect_zones.hpp"

namespace bemshape::geometry {

std::vector<char> faces_near_defects(const SurfaceMesh& mesh, const std::vector<DefectZone>& zones,
                                     double margin) {
  std::vector<char> flags(static_cast<std::size_t>(mesh.num_faces()), 0);
  if (zones.empty())
    return flags;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    Eigen::Vector3d lo = mesh.corner(f, 0), hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(mesh.corner(f, k));
      hi = hi.cwiseMax(mesh.corner(f, k));
    }
    for (const DefectZone& zone : zones) {
      const Eigen::Vector3d zone_lo = zone.box.min.array() - margin;
      const Eigen::Vector3d zone_hi = zone.box.max.array() + margin;
      if ((lo.array() <= zone_hi.array()).all() && (hi.array() >= zone_lo.array()).all()) {
        flags[static_cast<std::size_t>(f)] = 1;
        break;
      }
    }
  }
  return flags;
}

}  // namespace bemshape::geometry
