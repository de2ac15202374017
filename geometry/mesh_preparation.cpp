#include "geometry/mesh_preparation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "geometry/mesh_orientation.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/nonmanifold_split.hpp"
#include "geometry/self_intersection.hpp"
#include "geometry/surface_repair.hpp"

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
  WeldResult weld = weld_vertices(*input_vertices, soup.faces, options.weld_relative_tolerance);
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

  // Bodies exported on one grid without being united share faces once welded: their union,
  // before the duplicates are dropped (which would leave holes where they overlap).
  if (SharedFaceUnion united = unite_bodies_sharing_faces(weld.vertices, weld.faces); united.ok) {
    add_problem(report, Status::repaired, 1, united.step.where,
                "bodies sharing faces (the same triangles in both after welding)",
                "replaced by their union, the boundary of the region they enclose (see the repairs)");
    report.repairs.push_back(united.step.description);
    weld.vertices = std::move(united.vertices);
    weld.faces = std::move(united.faces);
  }

  throw_if_cancelled();
  report_progress(progress, "validation", 0.2);
  const MeshValidation before = validate_mesh(weld.vertices, weld.faces);
  const FaceCleanup cleanup = remove_degenerate_faces(weld.vertices, weld.faces);
  const double diagonal =
      cleanup.vertices.rows() > 0
          ? (cleanup.vertices.colwise().maxCoeff() - cleanup.vertices.colwise().minCoeff()).norm()
          : 0.0;
  const double repair_length = options.repair_length > 0.0
                                   ? options.repair_length
                                   : kRepairRelativeLength * diagonal;
  report.repair_length = repair_length;
  const std::string tolerance =
      "the repair length " + format_number(repair_length) +
      (options.repair_length > 0.0
           ? ""
           : " (" + format_number(100.0 * kRepairRelativeLength) +
                 " % of the bounding-box diagonal)");

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
  if (cleanup.collapsed_removed > 0)
    report.repairs.push_back(
        "removed " + counted(cleanup.collapsed_removed, "collapsed face", "collapsed faces") +
        " (first at " + format_point(before.collapsed_faces.first) + ")");
  if (cleanup.duplicates_removed > 0)
    report.repairs.push_back(
        "removed " + counted(cleanup.duplicates_removed, "duplicate face", "duplicate faces") +
        " (first at " + format_point(before.duplicate_faces.first) + ")");
  if (cleanup.zero_area_removed > 0)
    report.repairs.push_back(
        "removed " + counted(cleanup.zero_area_removed, "zero-area face", "zero-area faces") +
        " (first at " + format_point(before.zero_area_faces.first) + ")");

  // Cut non-manifold edges and vertices apart (the surface does not move).
  Eigen::MatrixX3d V = cleanup.vertices;
  Eigen::MatrixX3i F = cleanup.faces;
  NonmanifoldSplit split;
  if (options.repair_surface && (before.nonmanifold_edges || before.nonmanifold_vertices)) {
    split = split_nonmanifold(V, F);
    if (split.edges_split > 0) {
      add_problem(report, Status::repaired, split.edges_split, split.first_edge,
                  counted(split.edges_split, "non-manifold edge", "non-manifold edges") +
                      " (shared by more than two faces)",
                  "split: the faces around each edge were paired by angle, so bodies that "
                  "touch along an edge are separated; the surface is unchanged" +
                      std::string(split.faces_unpaired > 0
                                      ? " (" + counted(split.faces_unpaired, "face", "faces") +
                                            " without a partner kept an open edge)"
                                      : "") +
                      std::string(split.edges_crossing > 0
                                      ? "; along " +
                                            counted(split.edges_crossing, "edge", "edges") +
                                            " (first at " + format_point(split.first_crossing) +
                                            ") bodies pass through each other (see the "
                                            "overlapping bodies below)"
                                      : ""));
      report.repairs.push_back("split " +
                               counted(split.edges_split, "non-manifold edge", "non-manifold edges") +
                               " (first at " + format_point(split.first_edge) +
                               ") by pairing the faces around each by angle");
    }
    if (before.nonmanifold_vertices && split.vertices_split > 0) {
      add_problem(report, Status::repaired, before.nonmanifold_vertices.count,
                  before.nonmanifold_vertices.first,
                  counted(before.nonmanifold_vertices.count, "non-manifold vertex",
                          "non-manifold vertices") +
                      " (surface sheets meet only at a point)",
                  "duplicated, one copy per sheet; the surface is unchanged");
    }
    if (split.copies_added > 0)
      report.repairs.push_back("duplicated " +
                               counted(split.vertices_split, "vertex", "vertices") +
                               " shared by separate fans of faces into " +
                               std::to_string(split.vertices_split + split.copies_added) +
                               " copies (first at " + format_point(split.first_vertex) + ")");
    V = split.vertices;
    F = split.faces;
  }
  ConsistentOrientation consistent = orient_consistently(V, F);
  if (consistent.orientable && before.inconsistent_edges)
    add_problem(
        report, Status::repaired, before.inconsistent_edges.count, before.inconsistent_edges.first,
        counted(before.inconsistent_edges.count, "edge", "edges") +
            " between faces of opposite orientation",
        "made consistent by reversing " + counted(consistent.faces_flipped, "face", "faces"));
  if (consistent.orientable && consistent.faces_flipped > 0)
    report.repairs.push_back("reversed " + counted(consistent.faces_flipped, "face", "faces") +
                             " to make neighbouring faces agree");
  F = consistent.faces;

  // Stitch, drop loose open pieces, fill small holes.
  HoleClosing holes;
  MeshValidation after = validate_mesh(V, F);
  if (options.repair_surface && consistent.orientable && after.boundary_edges) {
    throw_if_cancelled();
    report_progress(progress, "holes", 0.3);
    holes = close_small_holes(V, F, repair_length);
    V = std::move(holes.vertices);
    F = std::move(holes.faces);
    if (holes.edges_stitched > 0)
      report.repairs.push_back("stitched " +
                               counted(holes.edges_stitched, "pair", "pairs") +
                               " of open edges with coinciding end points");
    if (!holes.pieces_removed.empty()) {
      double largest = 0.0;
      for (const SurfaceRepairStep& step : holes.pieces_removed)
        largest = std::max(largest, step.size);
      add_problem(report, Status::repaired, holes.pieces_removed.size(),
                  holes.pieces_removed.front().where,
                  counted(holes.pieces_removed.size(), "loose open piece", "loose open pieces") +
                      " up to " + format_number(largest) + " across",
                  "removed: each is at most " + tolerance + " across and encloses no solid");
      for (const SurfaceRepairStep& step : holes.pieces_removed)
        report.repairs.push_back(step.description);
    }
    if (!holes.holes_filled.empty()) {
      double largest = 0.0;
      for (const SurfaceRepairStep& step : holes.holes_filled)
        largest = std::max(largest, step.size);
      add_problem(report, Status::repaired, holes.holes_filled.size(),
                  holes.holes_filled.front().where,
                  counted(holes.holes_filled.size(), "hole", "holes") + " up to " +
                      format_number(largest) + " across",
                  "filled: each rim is at most " + tolerance +
                      " across; the patches continue the surface smoothly (flat on a flat rim)");
      for (const SurfaceRepairStep& step : holes.holes_filled)
        report.repairs.push_back(step.description);
    }
    after = validate_mesh(V, F);
  }

  // Refusals.
  if (after.boundary_edges) {
    std::string why = "the surface is not closed; close the holes in the CAD export (export a "
                      "closed solid, not a surface)";
    if (holes.holes_left > 0)
      why = counted(holes.holes_left, "hole", "holes") + " up to " +
            format_number(holes.largest_left) + " across" +
            (holes.largest_left > repair_length ? ", larger than " + tolerance
                                                : " (" + holes.why_left + ")") +
            ": " + why;
    add_problem(report, Status::refused, after.boundary_edges.count, after.boundary_edges.first,
                counted(after.boundary_edges.count, "open boundary edge", "open boundary edges"),
                why);
  }
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
    add_problem(report, Status::refused, cleanup.zero_area_left, before.zero_area_faces.first,
                counted(cleanup.zero_area_left, "zero-area face", "zero-area faces") +
                    " that cannot be removed",
                "they lie on a hole or a non-manifold edge; fix the surface in CAD");
  // Every face collapsed (e.g. all corners welded together): nothing is left to bound a
  // solid, and an empty mesh would pass every rule above (found by fuzz/fuzz_stl).
  if (F.rows() == 0 && !holes.pieces_removed.empty())
    add_problem(report, Status::refused, holes.pieces_removed.size(),
                holes.pieces_removed.front().where,
                "no face left after removing " +
                    counted(holes.pieces_removed.size(), "loose open piece", "loose open pieces"),
                "every piece of the surface is open and at most " + tolerance +
                    " across: the file holds no closed solid");
  else if (F.rows() == 0)
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
  bool closed = after.closed_manifold() && consistent.orientable && cleanup.zero_area_left == 0 &&
                F.rows() > 0;
  if (!after.nonmanifold_edges && !after.nonmanifold_vertices && consistent.orientable &&
      F.rows() > 0) {
    SelfIntersections si = find_self_intersections(V, F);
    if ((si.pairs > 0 || !split.crossing_edges.empty()) && options.repair_surface && closed) {
      IntersectionRepair fix =
          resolve_self_intersections(V, F, si, repair_length, split.crossing_edges);
      if (!fix.crossings_resolved.empty()) {
        double largest = 0.0;
        for (const SurfaceRepairStep& step : fix.crossings_resolved)
          largest = std::max(largest, step.size);
        add_problem(report, Status::repaired, fix.pairs_within_shells, si.first,
                    counted(fix.pairs_within_shells, "pair", "pairs") +
                        " of intersecting faces within a shell",
                    "the surface crosses itself in " +
                        counted(fix.crossings_resolved.size(), "region", "regions") +
                        " up to " + format_number(largest) +
                        " across: split along the curves where it crosses and replaced by the "
                        "boundary of the region it encloses (the points of positive winding "
                        "number, as for overlapping bodies); volume " +
                        format_number(fix.resolved_volume_before) +
                        " as given (overlaps counted twice), " +
                        format_number(fix.resolved_volume_after) + " after");
        for (const SurfaceRepairStep& step : fix.crossings_resolved)
          report.repairs.push_back(step.description);
      }
      if (!fix.clusters_replaced.empty()) {
        double largest = 0.0;
        for (const SurfaceRepairStep& step : fix.clusters_replaced)
          largest = std::max(largest, step.size);
        add_problem(report, Status::repaired, fix.pairs_within_shells, si.first,
                    counted(fix.pairs_within_shells, "pair", "pairs") +
                        " of intersecting faces within a shell",
                    "cut out and refilled in " +
                        counted(fix.clusters_replaced.size(), "region", "regions") + " up to " +
                        format_number(largest) + " across (at most " + tolerance +
                        "); volume changed by " + format_number(fix.volume_change));
        for (const SurfaceRepairStep& step : fix.clusters_replaced)
          report.repairs.push_back(step.description);
      }
      if (!fix.unions.empty()) {
        add_problem(report, Status::repaired, fix.unions.size(), fix.unions.front().where,
                    counted(fix.unions.size(), "group", "groups") + " of overlapping bodies",
                    "replaced by the boundary of their union: the solid is the set of points "
                    "inside any body (the positive fill rule of 3MF), which is unchanged");
        for (const SurfaceRepairStep& step : fix.unions)
          report.repairs.push_back(step.description);
      }
      V = std::move(fix.vertices);
      F = std::move(fix.faces);
      si = std::move(fix.left);
      if ((si.pairs > 0 || fix.crossings_left) && options.measure_defects &&
          !fix.unresolved.empty()) {
        // Measured on the surface as given: the regions are reported and marked.
        const DefectZone& largest = fix.unresolved.front();
        const std::size_t count = si.pairs > 0 ? si.pairs : split.edges_crossing;
        add_problem(report, Status::defect, count,
                    si.pairs > 0 ? si.first : split.first_crossing,
                    si.pairs > 0 ? counted(si.pairs, "pair", "pairs") + " of intersecting faces"
                                 : counted(split.edges_crossing, "edge", "edges") +
                                       " along which bodies pass through each other",
                    "not repaired in " +
                        counted(fix.unresolved.size(), "region", "regions") + ", the largest " +
                        format_number(largest.size()) + " across around " +
                        format_point(largest.centre()) + ": " + largest.why +
                        " (" + tolerance +
                        "); measured on the surface as given, the faces within h0 of each "
                        "region marked 'defect'; to measure the part as designed, unite the "
                        "bodies or remove the crossing in CAD");
        report.defects = std::move(fix.unresolved);
      } else if (si.pairs > 0) {
        closed = false;
        add_problem(report, Status::refused, si.pairs, si.first,
                    counted(si.pairs, "pair", "pairs") + " of intersecting faces",
                    "not repaired: " + fix.why_left + " (" + tolerance +
                        "); unite the bodies (boolean union) or separate them in CAD");
      } else if (fix.crossings_left) {
        closed = false;
        add_problem(report, Status::refused, split.edges_crossing, split.first_crossing,
                    counted(split.edges_crossing, "edge", "edges") +
                        " along which bodies pass through each other",
                    "not repaired: " + fix.why_left +
                        "; unite the bodies (boolean union) or separate them in CAD");
      }
      // The repairs must leave a closed, consistently oriented surface; check it again.
      consistent = orient_consistently(V, F);
      F = consistent.faces;
      after = validate_mesh(V, F);
      if (!after.closed_manifold() || !consistent.orientable) {
        closed = false;
        add_problem(report, Status::refused, after.boundary_edges.count + after.nonmanifold_edges.count,
                    after.boundary_edges ? after.boundary_edges.first : after.nonmanifold_edges.first,
                    "the self-intersection repair left an open or non-manifold surface",
                    "unite the bodies (boolean union) or remove the crossing in CAD");
      }
    } else if (si.pairs > 0) {
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

  // Whatever the repairs did, an empty mesh bounds nothing (and passes every rule above).
  if (F.rows() == 0 && report.usable())
    add_problem(report, Status::refused, 0, Eigen::Vector3d::Zero(), "no face left",
                "the repairs removed every face: the file holds no closed solid");

  throw_if_cancelled();
  report_progress(progress, "orientation", 0.8);
  if (closed) {
    const VolumeOrientation oriented = orient_to_bound_volume(V, F);
    F = oriented.faces;
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
      report.repairs.push_back("reversed " + counted(oriented.faces_flipped, "face", "faces") +
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

  PreparedMesh result{SurfaceMesh(std::move(V), std::move(F)), std::move(report)};
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
