#include "geometry/graded_remeshing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "geometry/detail/cgal_graded_remeshing.hpp"

namespace bemshape::geometry {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// An output face with a smallest angle below this [degrees] counts as degenerate: it is a
/// failure of the remesher (whose guards keep angles far above it), reported as such.
constexpr double kDegenerateAngleDegrees = 1e-3;

/// Split bound of the remesher (Botsch–Kobbelt's 4/3): an input whose edges are all within
/// it of h needs no split.
constexpr double kFineEnoughEdgeRatio = 4.0 / 3.0;

double min_angle_degrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& c) {
  const Eigen::Vector3d p[3] = {a, b, c};
  double smallest = 180.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
    smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)) / kDegree);
  }
  return smallest;
}

/// Fills `r`'s description of `m` against `field`: counts, edge range, smallest angle, the
/// edges' lengths against h at their midpoints, the area per reason of the size.
void describe_mesh(const SurfaceMesh& m, const SurfaceCreases& creases, const MeshSizeField& field,
                   GradedMeshReport& r) {
  r.faces = m.num_faces();
  r.vertices = m.num_vertices();
  r.creases = static_cast<int>(creases.creases.size());
  r.smoothed_edges = creases.smoothed_edges();
  r.field = field.summary();
  // Per face: smallest angle, the reason of the size at the centroid, the edges' lengths
  // against h at their midpoints (each edge twice, once from each face).
  const Eigen::Index nf = m.num_faces();
  Eigen::VectorXd angle(nf), shortest(nf), longest(nf), low(nf), high(nf), perimeter(nf), faces(nf);
  Eigen::VectorXi reason(nf);
#pragma omp parallel for schedule(static)
  for (Eigen::Index f = 0; f < nf; ++f) {
    angle(f) = min_angle_degrees(m.corner(f, 0), m.corner(f, 1), m.corner(f, 2));
    const auto [size, why] = field.size_and_reason(m.face_centroids().row(f).transpose());
    reason(f) = static_cast<int>(why);
    faces(f) = m.face_areas()(f) / (kEquilateralArea * size * size);
    shortest(f) = low(f) = std::numeric_limits<double>::infinity();
    longest(f) = high(f) = perimeter(f) = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = m.corner(f, k), b = m.corner(f, (k + 1) % 3);
      const double length = (b - a).norm();
      const double ratio = length / field.size(0.5 * (a + b));
      perimeter(f) += length;
      shortest(f) = std::min(shortest(f), length);
      longest(f) = std::max(longest(f), length);
      low(f) = std::min(low(f), ratio);
      high(f) = std::max(high(f), ratio);
    }
  }
  Eigen::Index worst = 0;
  r.min_angle_degrees = nf > 0 ? angle.minCoeff(&worst) : 180.0;
  if (nf > 0)
    r.worst_angle_at = m.face_centroids().row(worst).transpose();
  r.area_by_reason = {};
  for (Eigen::Index f = 0; f < nf; ++f)
    r.area_by_reason[static_cast<std::size_t>(reason(f))] += m.face_areas()(f);
  r.min_edge = shortest.minCoeff();
  r.max_edge = longest.maxCoeff();
  r.min_edge_ratio = low.minCoeff();
  r.max_edge_ratio = high.maxCoeff();
  r.mean_edge = perimeter.sum() / (3.0 * static_cast<double>(std::max<Eigen::Index>(nf, 1)));
  r.field_faces = faces.sum();
}

/// Whether every face of `m` has all its angles at least `degrees`.
bool smallest_angle_at_least(const SurfaceMesh& m, double degrees) {
  const Eigen::Index nf = m.num_faces();
  bool all = true;
#pragma omp parallel for schedule(static) reduction(&& : all)
  for (Eigen::Index f = 0; f < nf; ++f)
    all = all && min_angle_degrees(m.corner(f, 0), m.corner(f, 1), m.corner(f, 2)) >= degrees;
  return all;
}

}  // namespace

GradedMesh remesh_to_size_field(const SurfaceMesh& mesh, const SurfaceCreases& creases,
                                const MeshSizeField& field, const GradedRemeshingOptions& options,
                                const ProgressCallback& progress) {
  if (mesh.empty())
    throw InputError("cannot remesh an empty mesh");
  throw_if_cancelled();
  report_progress(progress, "remeshing", 0.0);
  detail::GradedRemeshInput input;
  input.vertices = &mesh.vertices();
  input.faces = &mesh.faces();
  input.creases.reserve(creases.creases.size());
  for (const DihedralEdge& c : creases.creases)
    input.creases.push_back({c.a, c.b});
  // Curved crease vertices are corners of the size field's straight pieces but not of the
  // remesher: they slide along the crease polygon and may be dropped.
  std::vector<char> fixed = creases.corner;
  bool curved = false;
  for (std::size_t v = 0; v < creases.curved.size(); ++v)
    if (creases.curved[v]) {
      fixed[v] = 0;
      curved = true;
    }
  input.corner = &fixed;
  input.curved_creases = curved;
  input.face_patch = &creases.face_patch;
  input.patches = creases.patches;
  input.size = [&field](const Eigen::Vector3d& x) { return field.size(x); };
  input.iterations = options.iterations;
  input.min_angle = options.min_angle_degrees * kDegree;
  input.max_normal_turn = options.max_normal_turn_degrees * kDegree;
  input.max_faces = options.max_faces;
  input.max_edge_ratio = options.max_edge_ratio;
  input.progress = [&progress](double fraction) {
    throw_if_cancelled();
    report_progress(progress, "remeshing", fraction);
  };
  detail::GradedRemeshOutput out = detail::cgal_graded_remesh(input);

  GradedMesh result{SurfaceMesh(std::move(out.vertices), std::move(out.faces)), {}};
  GradedMeshReport& r = result.report;
  r.splits = out.splits;
  r.collapses = out.collapses;
  r.flips = out.flips;
  r.moves = out.moves;
  describe_mesh(result.mesh, creases, field, r);
  if (r.min_angle_degrees < kDegenerateAngleDegrees) {
    std::ostringstream msg;
    msg << "bemshape's remeshing made a degenerate triangle (smallest angle "
        << r.min_angle_degrees << "°) at " << r.worst_angle_at.transpose()
        << "; this is a defect of the remesher, not of the input: please report it with the "
           "input file";
    throw InternalError(msg.str());
  }
  report_progress(progress, "remeshing", 1.0);
  return result;
}

GradedMesh graded_solver_mesh(const SurfaceMesh& mesh, const GradedMeshParameters& p,
                              const ProgressCallback& progress) {
  if (!(std::isfinite(p.h0) && p.h0 > 0.0))
    throw InputError("graded solver mesh: h0 must be a positive length");
  CreaseOptions crease_options;
  crease_options.crease_angle_degrees = p.crease_angle_degrees;
  crease_options.smooth_angle_degrees = p.smooth_angle_degrees;
  crease_options.chord_tolerance = p.chord_tolerance_ratio * p.h0;
  crease_options.min_chord = p.min_chord_ratio * p.fine_edge;
  crease_options.normal_scale = p.normal_scale_ratio * p.h0;
  crease_options.require_facet_strips = p.require_facet_strips;
  crease_options.curve_turn_degrees = p.curve_turn_degrees;
  const SurfaceCreases creases = find_surface_creases(mesh, crease_options);
  SizeFieldParameters field_parameters;
  field_parameters.fine_edge = p.fine_edge;
  field_parameters.max_edge = std::max(p.max_edge_ratio * p.h0, p.fine_edge);
  field_parameters.gradation = p.gradation;
  field_parameters.curvature_gradation = p.curvature_gradation;
  field_parameters.thin_wall = p.thin_wall_ratio * p.h0;
  field_parameters.wall_thickness_ratio = p.wall_thickness_ratio;
  field_parameters.curvature_ratio = p.curvature_ratio;
  field_parameters.crease_spacing_ratio = p.crease_spacing_ratio;
  field_parameters.sample_spacing = kThicknessSampleSpacing * p.h0;
  field_parameters.refine_creases = p.refine_creases;
  field_parameters.min_size = p.min_size_ratio * p.fine_edge;
  field_parameters.chord_thickness_ratio = p.chord_thickness_ratio;
  const MeshSizeField field(mesh, creases, field_parameters);
  if (p.keep_input_face_ratio > 0.0 && smallest_angle_at_least(mesh, p.remeshing.min_angle_degrees)) {
    // An input already as fine as the field asks, well shaped, and not much finer: remeshing
    // would only move its triangles around. The angle comes first: it needs no size query,
    // and a fine CAD export's slivers fail it (the tube's 69k faces: 0.4 s of queries saved).
    GradedMesh kept{mesh, {}};
    describe_mesh(mesh, creases, field, kept.report);
    const GradedMeshReport& r = kept.report;
    if (r.max_edge_ratio <= kFineEnoughEdgeRatio &&
        r.min_angle_degrees >= p.remeshing.min_angle_degrees &&
        static_cast<double>(r.faces) <= p.keep_input_face_ratio * r.field_faces) {
      kept.report.kept_input = true;
      report_progress(progress, "remeshing", 1.0);
      return kept;
    }
  }
  return remesh_to_size_field(mesh, creases, field, p.remeshing, progress);
}

}  // namespace bemshape::geometry
