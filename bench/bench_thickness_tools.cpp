// The wall thickness of CAD-like parts by bemshape and by the tools a user would otherwise
// run, side by side in one run on the same machine and the same parts: docs/validation.md,
// "bemshape beside CGAL's shape diameter function and a ray along the inward normal".
//
//   bench_thickness_tools [--threads N] [PART ...]
//
// PART is a labelled part (tests/support/labelled_parts.hpp; h0 = 0.9 × its nominal wall) or
// plate_holes (tests/data/meshes/plate_holes.STL, h0 = 0.9 × 12.7). Without parts: every
// labelled part but the large tray, and plate_holes. Each part is read as its STL export
// would be (welded, validated, repaired) and given to every tool as it is (the peers on the
// part's own mesh, as a user would run them):
//
//   bemshape  analysis::measure_thickness with the defaults (the wall measure on the uniform
//             default solver mesh 1.5·a·h0)
//   sdf       CGAL::sdf_values (Shapira et al. 2008), cone 2π/3, 25 rays, raw values (the
//             post-processing normalises them to [0, 1], which is no length)
//   ray       the distance from each face's centroid along −n to the first other face
//             (CGAL's AABB tree)
//
// For each tool: wall time [s] (bemshape: the whole measure_thickness call after reading;
// the peers: building their structures and computing every face), then against the design
// (the labels of the part, area-weighted over the tool's faces): median and 5th percentile
// of reading/design on the nominal walls, the share of the nominal walls' area read below
// 0.9 of their design (what a check at 0.9·t flags wrongly), and the smallest reading/design
// on the thin features. plate_holes has no labels: its broad faces (normal along the thinnest
// axis of the bounding box) are its nominal wall of 12.7. The last column: time over CGAL's
// SDF.

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/mesh_segmentation.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_thickness.hpp"
#include "core/errors.hpp"
#include "tests/support/labelled_parts.hpp"
#include "geometry/mesh_preparation.hpp"

using namespace bemshape;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

/// A ray starts this fraction of the part's diagonal inside the face, so that it does not hit
/// its own face or a neighbour at the start.
constexpr double kRayOffset = 1e-7;

struct Part {
  std::string name;
  geometry::SurfaceMesh mesh;
  double h0 = 0.0;
  /// Label of a face from its centroid and outward normal.
  std::function<testing::WallLabel(const Eigen::Vector3d&, const Eigen::Vector3d&)> label;
};

/// Readings of one tool on its own faces, against the design.
struct Reading {
  double seconds = 0.0;
  long faces = 0;
  double median = NAN, p05 = NAN, thin_min = NAN;  ///< reading / design
  double low = NAN;  ///< share of the nominal walls' area read below 0.9 of the design
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Area-weighted quantile q of values (weights ≥ 0); NaN for no weight.
double weighted_quantile(std::vector<std::pair<double, double>> values, double q) {
  std::sort(values.begin(), values.end());
  double total = 0.0;
  for (const auto& [v, w] : values)
    total += w;
  if (!(total > 0.0))
    return NAN;
  double sum = 0.0;
  for (const auto& [v, w] : values) {
    sum += w;
    if (sum >= q * total)
      return v;
  }
  return values.back().first;
}

/// The statistics of `thickness` (#F of `mesh`, NaN where the tool has no reading) against
/// the part's labels.
void score(const Part& part, const geometry::SurfaceMesh& mesh, const Eigen::VectorXd& thickness,
           Reading& r) {
  std::vector<std::pair<double, double>> nominal;
  double thin_min = std::numeric_limits<double>::infinity(), nominal_area = 0.0, low_area = 0.0;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    const testing::WallLabel label =
        part.label(mesh.face_centroids().row(f).transpose(), mesh.face_normals().row(f).transpose());
    if (!std::isfinite(thickness(f)) || !(label.thickness > 0.0))
      continue;
    const double ratio = thickness(f) / label.thickness;
    if (label.role == testing::WallRole::nominal) {
      nominal.emplace_back(ratio, mesh.face_areas()(f));
      nominal_area += mesh.face_areas()(f);
      if (ratio < 0.9)
        low_area += mesh.face_areas()(f);
    }
    else if (label.role == testing::WallRole::thin_feature)
      thin_min = std::min(thin_min, ratio);
  }
  r.faces = static_cast<long>(mesh.num_faces());
  r.median = weighted_quantile(nominal, 0.5);
  r.p05 = weighted_quantile(nominal, 0.05);
  r.thin_min = std::isfinite(thin_min) ? thin_min : NAN;
  r.low = nominal_area > 0.0 ? low_area / nominal_area : NAN;
}

Mesh to_cgal(const geometry::SurfaceMesh& m) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for (Eigen::Index i = 0; i < m.num_vertices(); ++i)
    v.push_back(mesh.add_vertex({m.vertices()(i, 0), m.vertices()(i, 1), m.vertices()(i, 2)}));
  for (Eigen::Index f = 0; f < m.num_faces(); ++f)
    mesh.add_face(v[static_cast<std::size_t>(m.faces()(f, 0))],
                  v[static_cast<std::size_t>(m.faces()(f, 1))],
                  v[static_cast<std::size_t>(m.faces()(f, 2))]);
  return mesh;
}

Reading run_sdf(const Part& part) {
  Reading r;
  const auto start = std::chrono::steady_clock::now();
  Mesh mesh = to_cgal(part.mesh);
  auto sdf = mesh.add_property_map<Mesh::Face_index, double>("f:sdf", 0.0).first;
  CGAL::sdf_values(mesh, sdf, 2.0 / 3.0 * CGAL_PI, 25, false);
  r.seconds = seconds_since(start);
  Eigen::VectorXd thickness(part.mesh.num_faces());
  Eigen::Index f = 0;
  for (Mesh::Face_index fi : mesh.faces())
    thickness(f++) = sdf[fi] > 0.0 ? sdf[fi] : NAN;  // −1: no ray came back
  score(part, part.mesh, thickness, r);
  return r;
}

Reading run_ray(const Part& part) {
  Reading r;
  const auto start = std::chrono::steady_clock::now();
  const Mesh mesh = to_cgal(part.mesh);
  Tree tree(faces(mesh).first, faces(mesh).second, mesh);
  tree.accelerate_distance_queries();
  const geometry::SurfaceMesh& m = part.mesh;
  const double offset = kRayOffset * m.bounding_box().diagonal();
  Eigen::VectorXd thickness(m.num_faces());
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d n = m.face_normals().row(f).transpose();
    const Eigen::Vector3d c = m.face_centroids().row(f).transpose() - offset * n;
    const Kernel::Ray_3 ray({c.x(), c.y(), c.z()}, Kernel::Vector_3(-n.x(), -n.y(), -n.z()));
    double best = NAN;
    // The nearest hit of any face; rays along a face's plane (which the AABB tree's first
    // intersection would need a predicate for) are rare and skipped.
    std::vector<Tree::Intersection_and_primitive_id<Kernel::Ray_3>::Type> hits;
    tree.all_intersections(ray, std::back_inserter(hits));
    for (const auto& hit : hits)
      if (const Kernel::Point_3* p = boost::get<Kernel::Point_3>(&hit.first)) {
        const double d = std::sqrt(CGAL::squared_distance(*p, ray.source())) + offset;
        if (!(d >= best))
          best = d;
      }
    thickness(f) = best;
  }
  r.seconds = seconds_since(start);
  score(part, m, thickness, r);
  return r;
}

Reading run_bemshape(const Part& part) {
  Reading r;
  analysis::ThicknessOptions options;
  options.solve.h0 = part.h0;
  options.map_to_input = false;
  const geometry::PreparedMesh input = analysis::prepare_triangles(part.mesh.vertices(),
                                                                   part.mesh.faces(), part.name);
  const auto start = std::chrono::steady_clock::now();
  const analysis::ThicknessResult result = analysis::measure_thickness(input, options);
  r.seconds = seconds_since(start);
  score(part, result.boundary.solver_mesh, result.thickness, r);
  return r;
}

Part labelled(const std::string& name) {
  testing::LabelledPart p = testing::make_labelled_part(name);
  const double h0 = 0.9 * p.nominal_wall;
  return {name, analysis::prepare_triangles(p.mesh.vertices(), p.mesh.faces(), name).mesh, h0,
          p.label};
}

Part plate_holes() {
  const geometry::PreparedMesh prepared =
      geometry::prepare_mesh_file(std::string(BEMSHAPE_TEST_DATA_DIR) + "/meshes/plate_holes.STL");
  const geometry::BoundingBox box = prepared.mesh.bounding_box();
  Eigen::Index axis = 0;
  const double thickness = box.extent().minCoeff(&axis);
  auto label = [axis, thickness](const Eigen::Vector3d&, const Eigen::Vector3d& n) {
    testing::WallLabel l;
    if (std::abs(n(axis)) > 0.999) {
      l.role = testing::WallRole::nominal;
      l.thickness = thickness;
    } else {
      l.thickness = NAN;
    }
    return l;
  };
  return {"plate_holes", prepared.mesh, 0.9 * thickness, label};
}

void print(const std::string& part, const std::string& tool, const Reading& r,
           double sdf_seconds) {
  std::printf("%-14s %-9s %8ld %8.2f %7.4f %7.4f %7.2f%% %7.4f %7.2f\n", part.c_str(),
              tool.c_str(), r.faces, r.seconds, r.median, r.p05, 100.0 * r.low, r.thin_min,
              r.seconds / sdf_seconds);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--threads" && i + 1 < argc) {
      omp_set_num_threads(std::stoi(argv[++i]));
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "usage: bench_thickness_tools [--threads N] [PART ...]\n");
      return 2;
    } else {
      names.push_back(arg);
    }
  }
  if (names.empty()) {
    names = testing::labelled_part_names();
    names.erase(std::remove(names.begin(), names.end(), "large-tray"), names.end());
    names.push_back("plate_holes");
  }
  std::printf("%-14s %-9s %8s %8s %7s %7s %8s %7s %7s\n", "part", "tool", "faces", "time[s]",
              "median", "p05", "<0.9t", "thinmin", "/sdf");
  try {
    for (const std::string& name : names) {
      const Part part = name == "plate_holes" ? plate_holes() : labelled(name);
      const Reading sdf = run_sdf(part);
      const Reading ray = run_ray(part);
      const Reading bemshape = run_bemshape(part);
      print(part.name, "sdf", sdf, sdf.seconds);
      print(part.name, "ray", ray, sdf.seconds);
      print(part.name, "bemshape", bemshape, sdf.seconds);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_thickness_tools: %s\n", e.what());
    return 1;
  }
  return 0;
}
