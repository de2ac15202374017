#include "geometry/mesh_preparation.hpp"

#include <Eigen/Geometry>
#include <cstdio>
#include <sstream>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "geometry/mesh_orientation.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/self_intersection.hpp"

namespace bemshape::geometry {
namespace {

using Status = MeshProblem::Status;

std::string format_point(const Eigen::Vector3d& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%.6g, %.6g, %.6g", p.x(), p.y(), p.z());
  return buffer;
}

std::string format_number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", x);
  return buffer;
}

/// A factor such as 25.4 or 304.8 with all its digits.
std::string format_factor(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", x);
  return buffer;
}

/// "1 open boundary edge" / "12 open boundary edges".
std::string counted(std::size_t n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

void add_problem(MeshReport& report, Status status, std::size_t count, const Eigen::Vector3d& first,
                 std::string what, std::string consequence) {
  MeshProblem problem;
  problem.status = status;
  problem.count = count;
  problem.first = first;
  problem.what = std::move(what);
  problem.consequence = std::move(consequence);
  report.problems.push_back(std::move(problem));
}

}  // namespace

std::string MeshProblem::describe() const {
  return what + " (first at " + format_point(first) + "): " + consequence;
}

bool MeshReport::usable() const {
  for (const MeshProblem& p : problems)
    if (p.status == Status::refused)
      return false;
  return true;
}

std::string MeshReport::refusal_message() const {
  std::string message;
  for (const MeshProblem& p : problems) {
    if (p.status != Status::refused)
      continue;
    if (message.empty())
      message = source + ": " + p.describe();
    else
      message += "\n  also: " + p.describe();
  }
  return message;
}

PreparedMesh inspect_triangle_soup(const TriangleSoup& soup, const std::string& source,
                                   const MeshPreparationOptions& options,
                                   const ProgressCallback& progress) {
  MeshReport report;
  report.source = source;
  report.format = soup.format;
  if (soup.build_items > 0)
    report.format += " (" + counted(soup.build_items, "build item", "build items") + ", " +
                     counted(soup.mesh_instances, "mesh", "meshes") + " placed)";
  report.triangles_read = static_cast<std::size_t>(soup.faces.rows());
  report.vertices_read = static_cast<std::size_t>(soup.vertices.rows());
  report.unit = soup.unit;
  for (const std::string& note : soup.notes)
    add_problem(report, Status::note, 0, Eigen::Vector3d::Zero(), "reader", note);

  // Unit conversion, only on request and only for a file that records its unit.
  Eigen::MatrixX3d converted;
  const Eigen::MatrixX3d* input_vertices = &soup.vertices;
  if (options.convert_to_millimetres) {
    if (soup.millimetres_per_unit <= 0.0) {
      add_problem(report, Status::note, 0, Eigen::Vector3d::Zero(), "no unit to convert",
                  "the " + soup.format +
                      " format records no length unit; coordinates are used as stored");
    } else if (soup.millimetres_per_unit != 1.0) {
      converted = soup.vertices * soup.millimetres_per_unit;
      input_vertices = &converted;
      report.converted_from = soup.unit;
      report.unit = "millimeter";
      report.repairs.push_back("converted the coordinates from " + soup.unit +
                               " to millimeter (x " + format_factor(soup.millimetres_per_unit) +
                               ")");
    }
  }

  // What the reader already did.
  if (soup.format.find("STL") != std::string::npos && soup.corners_in_file > report.vertices_read)
    report.repairs.push_back("merged " + std::to_string(soup.corners_in_file) +
                             " facet corners with exactly equal coordinates into " +
                             std::to_string(report.vertices_read) + " vertices (STL reader)");
  if (soup.polygons_triangulated > 0)
    report.repairs.push_back("split " + counted(soup.polygons_triangulated, "polygon", "polygons") +
                             " with more than 3 corners into " +
                             std::to_string(soup.triangles_from_polygons) +
                             " triangles (fan from the first corner)");
  if (soup.collapsed_faces_dropped > 0)
    report.repairs.push_back("dropped " + counted(soup.collapsed_faces_dropped, "face", "faces") +
                             " with fewer than 3 distinct corners (reader)");

  throw_if_cancelled();
  report_progress(progress, "welding", 0.0);
  const WeldResult weld =
      weld_vertices(*input_vertices, soup.faces, options.weld_relative_tolerance);
  report.weld_tolerance = weld.tolerance;
  if (weld.merged_exact > 0)
    report.repairs.push_back("merged " + counted(weld.merged_exact, "vertex", "vertices") +
                             " with exactly equal coordinates");
  if (weld.merged_within_tolerance > 0)
    report.repairs.push_back(
        "merged " + counted(weld.merged_within_tolerance, "vertex", "vertices") + " closer than " +
        format_number(weld.tolerance) + " (" + format_number(options.weld_relative_tolerance) +
        " of the bounding-box diagonal)");
  if (weld.unreferenced_removed > 0)
    report.repairs.push_back("dropped " + counted(weld.unreferenced_removed, "vertex", "vertices") +
                             " no face uses");

  throw_if_cancelled();
  report_progress(progress, "validation", 0.2);
  const MeshValidation before = validate_mesh(weld.vertices, weld.faces);
  const FaceCleanup cleanup = remove_degenerate_faces(weld.vertices, weld.faces);
  const ConsistentOrientation consistent = orient_consistently(cleanup.vertices, cleanup.faces);
  const MeshValidation after = validate_mesh(cleanup.vertices, consistent.faces);

  if (before.collapsed_faces)
    add_problem(report, Status::repaired, before.collapsed_faces.count,
                before.collapsed_faces.first,
                counted(before.collapsed_faces.count, "face", "faces") +
                    " with a repeated vertex after welding",
                "removed; their neighbours already close the surface");
  if (before.duplicate_faces)
    add_problem(report, Status::repaired, before.duplicate_faces.count,
                before.duplicate_faces.first,
                counted(before.duplicate_faces.count, "duplicate face", "duplicate faces"),
                "removed, one copy of each kept");
  if (before.zero_area_faces) {
    const std::string what =
        counted(before.zero_area_faces.count, "zero-area face", "zero-area faces") +
        " (collinear corners: height <= " + format_number(kZeroAreaRelativeHeight) +
        " of the longest edge)";
    if (cleanup.zero_area_left == 0)
      add_problem(report, Status::repaired, before.zero_area_faces.count,
                  before.zero_area_faces.first, what,
                  "removed by splitting the neighbour across the longest edge; the surface is "
                  "unchanged");
  }
  if (before.needle_faces)
    add_problem(report, Status::note, before.needle_faces.count, before.needle_faces.first,
                counted(before.needle_faces.count, "needle face", "needle faces") + " (height < " +
                    format_number(kNeedleRelativeHeight) + " of the longest edge)",
                "valid geometry, but too thin for boundary elements; remesh the surface "
                "(refine_to_edge_length) before a BEM solve");
  if (consistent.orientable && before.inconsistent_edges)
    add_problem(
        report, Status::repaired, before.inconsistent_edges.count, before.inconsistent_edges.first,
        counted(before.inconsistent_edges.count, "edge", "edges") +
            " between faces of opposite orientation",
        "made consistent by reversing " + counted(consistent.faces_flipped, "face", "faces"));

  // Refusals.
  if (after.boundary_edges)
    add_problem(report, Status::refused, after.boundary_edges.count, after.boundary_edges.first,
                counted(after.boundary_edges.count, "open boundary edge", "open boundary edges"),
                "the surface is not closed; close the holes in the CAD export (export a closed "
                "solid, not a surface)");
  if (after.nonmanifold_edges)
    add_problem(report, Status::refused, after.nonmanifold_edges.count,
                after.nonmanifold_edges.first,
                counted(after.nonmanifold_edges.count, "non-manifold edge", "non-manifold edges") +
                    " (shared by more than two faces)",
                "bodies touch along an edge or faces are doubled; merge the bodies into one "
                "solid or separate them in CAD");
  if (after.nonmanifold_vertices)
    add_problem(
        report, Status::refused, after.nonmanifold_vertices.count, after.nonmanifold_vertices.first,
        counted(after.nonmanifold_vertices.count, "non-manifold vertex", "non-manifold vertices") +
            " (surface sheets meet only at a point)",
        "bodies touch at a vertex; merge them into one solid or separate them in CAD");
  if (!consistent.orientable)
    add_problem(report, Status::refused, 1, consistent.non_orientable_at, "a non-orientable shell",
                "its faces cannot be oriented consistently, so it bounds no solid; re-export "
                "the part as a closed solid");
  if (cleanup.zero_area_left > 0)
    add_problem(report, Status::refused, cleanup.zero_area_left, after.zero_area_faces.first,
                counted(cleanup.zero_area_left, "zero-area face", "zero-area faces") +
                    " that cannot be removed",
                "they lie on a hole or a non-manifold edge; fix the surface in CAD");
  // Every face collapsed (e.g. all corners welded together): nothing is left to bound a
  // solid, and an empty mesh would pass every rule above (found by fuzz/fuzz_stl).
  if (consistent.faces.rows() == 0)
    add_problem(report, Status::refused, static_cast<std::size_t>(weld.faces.rows()),
                before.collapsed_faces.first,
                "no face left after removing " +
                    counted(static_cast<std::size_t>(weld.faces.rows()), "collapsed face",
                            "collapsed faces"),
                "every face has coinciding corners at the weld tolerance " +
                    format_number(weld.tolerance) +
                    "; check the file's coordinates (a few far-away vertices make the "
                    "tolerance, a fraction of the bounding box, too coarse)");

  throw_if_cancelled();
  report_progress(progress, "self-intersections", 0.4);
  bool closed = after.closed_manifold() && consistent.orientable && cleanup.zero_area_left == 0;
  if (!after.nonmanifold_edges && !after.nonmanifold_vertices && consistent.orientable &&
      consistent.faces.rows() > 0) {
    const SelfIntersections si = find_self_intersections(cleanup.vertices, consistent.faces);
    if (si.pairs > 0) {
      closed = false;
      add_problem(report, Status::refused, si.pairs, si.first,
                  counted(si.pairs, "pair", "pairs") + " of intersecting faces",
                  "the surface crosses itself or bodies overlap; unite the bodies (boolean "
                  "union) or separate them in CAD");
    }
  } else {
    add_problem(report, Status::note, 0, Eigen::Vector3d::Zero(), "self-intersection test skipped",
                "it needs a manifold, orientable surface");
  }

  throw_if_cancelled();
  report_progress(progress, "orientation", 0.8);
  Eigen::MatrixX3i faces = consistent.faces;
  if (closed) {
    const VolumeOrientation oriented = orient_to_bound_volume(cleanup.vertices, faces);
    faces = oriented.faces;
    report.cavities = oriented.cavities;
    if (oriented.shells_flipped > 0) {
      Eigen::Vector3d first = Eigen::Vector3d::Zero();
      for (const ShellOrientation& s : oriented.shells)
        if (s.flipped) {
          first = s.where;
          break;
        }
      add_problem(report, Status::repaired, oriented.shells_flipped, first,
                  counted(oriented.shells_flipped, "shell", "shells") +
                      " inside out (normals pointing into the solid)",
                  "reversed " + counted(oriented.faces_flipped, "face", "faces") +
                      " so that every shell bounds the solid");
    }
    std::size_t flat = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    for (const ShellOrientation& s : oriented.shells)
      if (s.volume == 0.0 && flat++ == 0)
        first = s.where;
    if (flat > 0)
      add_problem(report, Status::refused, flat, first,
                  counted(flat, "shell", "shells") + " enclosing no volume",
                  "a closed surface folded flat onto itself bounds no solid; remove it in CAD");
  }

  {
    if (cleanup.collapsed_removed + cleanup.duplicates_removed + cleanup.zero_area_removed > 0)
      report.repairs.push_back(
          "removed " + std::to_string(cleanup.collapsed_removed + cleanup.duplicates_removed) +
          " collapsed or duplicate faces and " + std::to_string(cleanup.zero_area_removed) +
          " zero-area faces");
    if (consistent.orientable && consistent.faces_flipped > 0)
      report.repairs.push_back("reversed " + counted(consistent.faces_flipped, "face", "faces") +
                               " to make neighbouring faces agree");
    for (const MeshProblem& p : report.problems)
      if (p.status == Status::repaired && p.what.find("inside out") != std::string::npos)
        report.repairs.push_back(p.consequence);
  }

  PreparedMesh result{SurfaceMesh(cleanup.vertices, faces), std::move(report)};
  MeshReport& r = result.report;
  r.faces = static_cast<std::size_t>(result.mesh.num_faces());
  r.vertices = static_cast<std::size_t>(result.mesh.num_vertices());
  r.shells = after.shells;
  r.volume = result.mesh.signed_volume();
  r.area = result.mesh.area();
  r.bounding_box = result.mesh.bounding_box();
  report_progress(progress, "orientation", 1.0);
  return result;
}

PreparedMesh inspect_mesh_file(const std::filesystem::path& path,
                               const MeshPreparationOptions& options,
                               const ProgressCallback& progress) {
  report_progress(progress, "reading", 0.0);
  const TriangleSoup soup = read_triangle_soup(path);
  throw_if_cancelled();
  return inspect_triangle_soup(soup, path.string(), options, progress);
}

PreparedMesh prepare_mesh_file(const std::filesystem::path& path,
                               const MeshPreparationOptions& options,
                               const ProgressCallback& progress) {
  PreparedMesh prepared = inspect_mesh_file(path, options, progress);
  if (!prepared.report.usable())
    throw InputError(prepared.report.refusal_message());
  return prepared;
}

PreparedMesh prepare_triangle_soup(const TriangleSoup& soup, const std::string& source,
                                   const MeshPreparationOptions& options,
                                   const ProgressCallback& progress) {
  PreparedMesh prepared = inspect_triangle_soup(soup, source, options, progress);
  if (!prepared.report.usable())
    throw InputError(prepared.report.refusal_message());
  return prepared;
}

}  // namespace bemshape::geometry
