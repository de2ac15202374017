#pragma once
// The whole input pipeline of the jobs (analysis/): read → weld → validate → repair → report.
//
//   1. read the file into a triangle soup (mesh_io.hpp; polygons fan-triangulated);
//   2. weld coincident vertices, exactly and within kWeldRelativeTolerance·diagonal;
//   3. validate (mesh_validation.hpp) and repair what carries no geometry: collapsed,
//      duplicate and zero-area faces (mesh_repair.hpp);
//   4. split non-manifold edges and vertices (nonmanifold_split.hpp), orient consistently;
//   5. stitch coinciding open edges, remove loose open pieces and fill holes at most the
//      repair length ℓ across (surface_repair.hpp);
//   6. find self-intersections; replace shells that cross themselves by the boundary of the
//      region they enclose where that solid is clear, cut out and refill clusters within a
//      shell at most ℓ across, unite overlapping bodies (surface_repair.hpp);
//   7. keep the crossings left as defects, measured around (MeshReport::defects), unless
//      MeshPreparationOptions::measure_defects is off;
//   8. refuse what is left: larger holes, non-orientable shells, zero-area faces on a hole,
//      shells that enclose no volume;
//   9. orient every shell to bound the solid (outer skins outward, cavity walls inward).
//
// Nothing is guessed: every change is listed in MeshReport::repairs, every defect in
// MeshReport::problems with its count and the position of its first occurrence.

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/progress.hpp"
#include "geometry/defect_zones.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/vertex_welding.hpp"

namespace bemshape::geometry {

/// One rule a mesh broke.
struct MeshProblem {
  /// defect: not repaired, but the analysis measures on the surface as given and marks the
  /// region (MeshReport::defects); the mesh stays usable.
  enum class Status { repaired, refused, note, defect };
  Status status = Status::refused;
  /// Short name with count, e.g. "12 open boundary edges".
  std::string what;
  std::size_t count = 0;
  /// Position of the first offender [model units].
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  /// Why it matters and what the user can do, e.g. "the surface is not closed; close the
  /// holes in the CAD export". For repaired problems: what was done.
  std::string consequence;

  /// "<what> (first at x, y, z): <consequence>".
  std::string describe() const;
};

struct MeshReport {
  std::string source;  // file name, or the name given for in-memory input
  std::string format;
  /// Length unit of the prepared mesh's coordinates: the unit the file records (3MF:
  /// "micron", "millimeter", "centimeter", "inch", "foot", "meter"), "millimeter" after a
  /// conversion, empty if the format records none (lengths are then in the file's units).
  std::string unit;
  /// The unit the file recorded if the coordinates were converted to millimetres; else empty.
  std::string converted_from;
  std::size_t triangles_read = 0;
  std::size_t vertices_read = 0;
  double weld_tolerance = 0.0;  // [model units]
  /// The repair length ℓ used [model units]: holes, loose pieces and self-intersecting
  /// regions at most this large were repaired, larger ones refused.
  double repair_length = 0.0;

  // The prepared mesh (meaningful in full only if usable()).
  std::size_t faces = 0;
  std::size_t vertices = 0;
  std::size_t shells = 0;
  std::size_t cavities = 0;
  double volume = 0.0;  // [model units³]
  double area = 0.0;    // [model units²]
  BoundingBox bounding_box;

  std::vector<MeshProblem> problems;
  /// Every change made to the input, in order, e.g. "merged 3 vertices closer than 2e-7".
  std::vector<std::string> repairs;
  /// Regions where the surface still crosses itself and is used as given (problems with
  /// status defect), largest first: the analysis marks the faces near them.
  std::vector<DefectZone> defects;

  bool usable() const;
  /// The refusal as the InputError message: first line "<source>: <first refused
  /// problem>", then one line per further refused problem. Empty if usable().
  std::string refusal_message() const;
};

struct PreparedMesh {
  SurfaceMesh mesh;
  MeshReport report;
};

struct MeshPreparationOptions {
  double weld_relative_tolerance = kWeldRelativeTolerance;
  /// Repair holes, non-manifold edges and vertices, loose pieces, small self-intersections
  /// and overlapping bodies (surface_repair.hpp, nonmanifold_split.hpp); false refuses them
  /// all, as a strict CAD check would.
  bool repair_surface = true;
  /// The repair length ℓ [model units]: the largest hole, loose piece or self-intersecting
  /// region that is repaired. 0 means kRepairRelativeLength (2 %) of the bounding-box
  /// diagonal; a caller that knows the length the analysis resolves (h0, the element size)
  /// passes it.
  double repair_length = 0.0;
  /// Where a self-crossing cannot be repaired, keep the surface as given, list the region in
  /// MeshReport::defects (status defect) and stay usable, so that the analysis measures
  /// around it; false refuses such a mesh.
  bool measure_defects = true;
  /// Scale the coordinates to millimetres when the file records its unit (3MF); a file
  /// without a unit (STL, OBJ, OFF, PLY) is used as stored, with a note. Off by default:
  /// lengths stay in the file's units, and the report names the unit.
  bool convert_to_millimetres = false;
};

/// Runs the pipeline on a file and reports; does not throw for mesh defects (check
/// report.usable()). Throws InputError if the file cannot be read at all.
PreparedMesh inspect_mesh_file(const std::filesystem::path& path,
                               const MeshPreparationOptions& options = {},
                               const ProgressCallback& progress = {});

/// The same for a triangle soup already in memory; `source` names it in messages.
PreparedMesh inspect_triangle_soup(const TriangleSoup& soup, const std::string& source,
                                   const MeshPreparationOptions& options = {},
                                   const ProgressCallback& progress = {});

/// What the solver stages call: inspect_mesh_file, then throw InputError with
/// report.refusal_message() if the mesh is not usable. The returned mesh is closed,
/// manifold, free of degenerate faces and outward-oriented, and free of self-intersections
/// outside the regions listed in report.defects.
PreparedMesh prepare_mesh_file(const std::filesystem::path& path,
                               const MeshPreparationOptions& options = {},
                               const ProgressCallback& progress = {});

/// The same for a triangle soup in memory (e.g. arrays from another program), named
/// `source` in messages: inspect_triangle_soup, then throw InputError if not usable.
PreparedMesh prepare_triangle_soup(const TriangleSoup& soup, const std::string& source,
                                   const MeshPreparationOptions& options = {},
                                   const ProgressCallback& progress = {});

}  // namespace bemshape::geometry
