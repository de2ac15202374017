#pragma once
// The body of the mesh-file harnesses (fuzz_stl, fuzz_obj, fuzz_off, fuzz_ply): read the
// bytes as a file of the given extension, then run validation and repair on what was read,
// and check the pipeline's promise: a mesh reported usable is closed, manifold, consistently
// oriented and free of self-intersections outside the defect regions it reports (every
// intersecting pair's crossing lies in one of them), every face index is in range and every
// coordinate finite.

#include <cstdlib>

#include <Eigen/Geometry>

#include "fuzz/fuzz_input.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/self_intersection.hpp"

namespace bemshape::fuzz {

/// Aborts (a finding) if a mesh the pipeline calls usable breaks its contract.
inline void check_prepared(const geometry::PreparedMesh& prepared) {
  if (!prepared.report.usable()) return;
  const auto& v = prepared.mesh.vertices();
  const auto& f = prepared.mesh.faces();
  if (f.rows() == 0 || !v.allFinite()) std::abort();
  if (f.size() > 0 && (f.minCoeff() < 0 || f.maxCoeff() >= v.rows())) std::abort();
  const geometry::MeshValidation validation = geometry::validate_mesh(v, f);
  if (!validation.closed_manifold() || validation.inconsistent_edges) std::abort();
  const geometry::SelfIntersections crossings = geometry::find_self_intersections(v, f);
  if (crossings.pairs == 0) return;
  const auto& zones = prepared.report.defects;
  if (zones.empty() || crossings.pairs > crossings.face_pairs.size()) std::abort();
  // The two faces' crossing lies in the intersection of their boxes; it must meet a zone.
  const auto box = [&](Eigen::Index face) {
    Eigen::AlignedBox3d b;
    for (int k = 0; k < 3; ++k) b.extend(Eigen::Vector3d(v.row(f(face, k))));
    return b;
  };
  for (const auto& [a, b] : crossings.face_pairs) {
    const Eigen::AlignedBox3d crossing = box(a).intersection(box(b));
    bool inside = false;
    for (const geometry::DefectZone& zone : zones)
      inside = inside || crossing.intersects(Eigen::AlignedBox3d(zone.box.min, zone.box.max));
    if (!inside) std::abort();
  }
}

inline int run_mesh_file(const std::uint8_t* data, std::size_t size, const char* extension) {
  const auto path = input_file(data, size, extension);
  refusal_allowed([&] {
    const geometry::TriangleSoup soup = geometry::read_triangle_soup(path);
    if (soup.faces.rows() > 0 && (soup.faces.minCoeff() < 0 ||
                                  soup.faces.maxCoeff() >= soup.vertices.rows()))
      std::abort();  // the reader promises valid indices
    check_prepared(geometry::inspect_triangle_soup(soup, path.string()));
  });
  return 0;
}

}  // namespace bemshape::fuzz
