// The wall thickness of CAD-like parts by bemshape and by the tools a user would otherwise
// run, side by side in one run on the same machine and the same files: docs/validation.md,
// "bemshape beside the tools users have", and the stage profile of docs/benchmarks.md, "A part
// in seconds".
//
//   bench_thickness_tools [--threads N] [--noise F ...] [--seed S] [--tools LIST]
//                         [--min-faces N] [--keep DIR] [--profile] [PART ...]
//
// PART is a labelled part (tests/support/labelled_parts.hpp) or plate_holes
// (tests/data/meshes/plate_holes.STL, its broad faces a nominal wall of 12.7). Without parts:
// every labelled part but the large tray, and plate_holes. Each part is exported as a user's
// CAD system would write it (tests/support/part_exports.hpp: round walls at a 0.01 mm chord,
// at least --min-faces triangles, default 50,000), optionally with seeded noise along the
// normals of σ = F × its nominal wall (--noise 0.01 0.03 0.05; 0, the clean export, is the
// default), written as binary STL, and every tool reads that file in a process of its own
// (this program run again with --run), so that its time counts from the file and its peak
// resident memory is its own:
//
//   bemshape  `bemshape thickness FILE --min-thickness 0.9t` through the library
//             (analysis::measure_thickness of the file, defaults otherwise; the boss-tab part
//             also with --max-thickness 6, to find its boss), scored on its solver faces
//   ray       the distance from each face's centroid along −n to the first other face
//             (CGAL's AABB tree): what trimesh, Blender and Meshmixer compute
//   sdf       CGAL::sdf_values (Shapira et al. 2008), cone 2π/3, 25 rays, raw values (the
//             post-processing normalises them to [0, 1], which is no length)
//   sphere    the diameter of the largest ball inside the part that touches the face's
//             centroid, by the shrinking-ball iteration (Ma, Bai, Shi, Chen 2012) on CGAL's
//             AABB tree: what inscribed-sphere tools (MeshLib) report
//
// --tools picks some of them (comma-separated, default all four). For each tool, against
// the design (the part's labels, area-weighted over the tool's faces, each face labelled by
// the nearest point of the clean part): wall time [s] and peak
// resident memory [MB] of its process, faces it read on, median and 5th percentile of
// reading/design on the nominal walls, the share of the nominal walls' area read below 0.9 of
// their design ("low": what a check at 0.9·t flags wrongly), and per thin feature the share of
// its area read below 0.9·t and the regions there (edge-connected sets of such faces, of at
// least h0²/4 for the peers; bemshape's own regions). --profile adds bemshape's stages.
// With BENCH_DUMP_DIR set, bemshape's solver faces are written there as <file>.csv with
// their labels and the mid-surface search's readings.

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/mesh_segmentation.h>
#include <omp.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/measure_thickness.hpp"
#include "analysis/thickness_statistics.hpp"
#include "apps/output/stl_writer.hpp"
#include "core/errors.hpp"
#include "core/heap_retention.hpp"
#include "core/huge_pages.hpp"
#include "core/memory.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/mesh_preparation.hpp"
#include "tests/support/labelled_parts.hpp"
#include "tests/support/part_exports.hpp"

using namespace bemshape;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

/// A ray starts this fraction of the part's diagonal inside the face, so that it does not hit
/// its own face or a neighbour at the start.
constexpr double kRayOffset = 1e-7;
/// The shrinking ball stops when its radius changes by less than this fraction.
constexpr double kBallTolerance = 1e-4;
constexpr int kBallIterations = 60;
/// Reading/design below this is what a check at 0.9·t flags.
constexpr double kCheckRatio = 0.9;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The part, its design wall and the options bemshape is run with.
struct PartSpec {
  std::string name;
  testing::LabelledPart part;
  double t = 0.0;                        ///< nominal wall [mm]
  double h0 = 0.0;                       ///< the check's limit 0.9·t, which bemshape takes as h0
  double max_thickness = 0.0;            ///< 0: none
};

PartSpec plate_holes_spec() {
  const geometry::PreparedMesh prepared =
      geometry::prepare_mesh_file(std::string(BEMSHAPE_TEST_DATA_DIR) + "/meshes/plate_holes.STL");
  const geometry::BoundingBox box = prepared.mesh.bounding_box();
  Eigen::Index axis = 0;
  const double thickness = box.extent().minCoeff(&axis);
  PartSpec spec;
  spec.name = "plate_holes";
  spec.t = thickness;
  spec.part.name = "plate_holes";
  spec.part.mesh = prepared.mesh;
  spec.part.nominal_wall = thickness;
  spec.part.label = [axis, thickness](const Eigen::Vector3d&, const Eigen::Vector3d& n) {
    testing::WallLabel l;
    if (std::abs(n(axis)) > 0.99) {
      l.role = testing::WallRole::nominal;
      l.thickness = thickness;
    } else {
      l.thickness = NAN;
    }
    return l;
  };
  return spec;
}

/// The part's specification; with `fine` its mesh is the fine export (else the coarse
/// CAD-like mesh, enough for its labels).
PartSpec part_spec(const std::string& name, bool fine, long min_faces) {
  PartSpec spec;
  if (name == "plate_holes") {
    spec = plate_holes_spec();
    if (fine) spec.part.mesh = testing::refined_to_faces(spec.part.mesh, min_faces);
  } else {
    spec.name = name;
    spec.part = fine ? testing::fine_export(name, min_faces) : testing::make_labelled_part(name);
    spec.t = spec.part.nominal_wall;
  }
  spec.h0 = kCheckRatio * spec.t;
  if (name == "large-tray") spec.h0 = spec.t;  // the tray is checked at h0 = its wall
  for (const auto& feature : spec.part.features)
    if (feature.role == testing::WallRole::thick_feature)
      spec.max_thickness = 1.5 * spec.t;
  if (name == "boss-tab") spec.max_thickness = 6.0;
  return spec;
}

/// What one tool read on its faces, scored against the design.
struct Score {
  double seconds = NAN, peak_mb = NAN;
  long faces = 0;
  double median = NAN, p05 = NAN, p95 = NAN, low = NAN;
  std::vector<double> thin_flagged;  ///< per thin feature: share of its area below 0.9·t
  std::vector<int> thin_regions;     ///< per thin feature: regions with faces on it
  int regions = 0;                   ///< regions in all
  int thick_found = -1;              ///< −1 no thick feature; 1 the thickest region is in it
  std::map<std::string, double> stages;  ///< bemshape's stage times [s] and counts
};

/// The labels of the faces of `mesh` (the part's surface, perhaps a noisy copy): each face
/// takes the label of the nearest point of the part's own surface, with the normal there, so
/// that a noisy face next to a rib is labelled by where it lies on the design, not by where
/// the noise moved its centroid.
std::vector<testing::WallLabel> design_labels(const PartSpec& spec,
                                              const geometry::SurfaceMesh& mesh) {
  const geometry::ClosestPointQuery design(spec.part.mesh);
  const geometry::ClosestPoints nearest = design.closest_points(mesh.face_centroids());
  std::vector<testing::WallLabel> labels(std::size_t(mesh.num_faces()));
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    labels[std::size_t(f)] = spec.part.label(
        nearest.points.row(f).transpose(),
        spec.part.mesh.face_normals().row(nearest.faces(f)).transpose());
  return labels;
}

/// Scores `thickness` (#F of `mesh`, NaN where the tool has no reading) against the labels.
/// `regions`: the tool's own thin regions if it has them; otherwise edge-connected sets of
/// faces below 0.9·t of at least h0²/4 (bemshape's default speck area).
void score(const PartSpec& spec, const geometry::SurfaceMesh& mesh,
           const Eigen::VectorXd& thickness, const std::vector<analysis::ThinRegion>* own,
           Score& s) {
  const std::vector<testing::WallLabel> labels = design_labels(spec, mesh);
  std::vector<double> ratio, area;
  double nominal_area = 0.0, low_area = 0.0;
  const std::size_t nfeatures = spec.part.features.size();
  std::vector<double> feature_area(nfeatures, 0.0), feature_low(nfeatures, 0.0);
  const double limit = kCheckRatio * spec.t;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    const testing::WallLabel& l = labels[std::size_t(f)];
    const double a = mesh.face_areas()(f);
    const double value = std::isfinite(thickness(f)) ? thickness(f) : 0.0;  // no reading: fails
    if (l.role == testing::WallRole::nominal && l.thickness > 0.0) {
      ratio.push_back(value / l.thickness);
      area.push_back(a);
      nominal_area += a;
      if (value < kCheckRatio * l.thickness) low_area += a;
    } else if (l.role == testing::WallRole::thin_feature) {
      feature_area[std::size_t(l.feature)] += a;
      if (value < limit) feature_low[std::size_t(l.feature)] += a;
    }
  }
  s.faces = long(mesh.num_faces());
  if (!ratio.empty()) {
    const Eigen::Map<const Eigen::VectorXd> r(ratio.data(), Eigen::Index(ratio.size()));
    const Eigen::Map<const Eigen::VectorXd> w(area.data(), Eigen::Index(area.size()));
    s.median = analysis::weighted_quantile(r, w, 0.5);
    s.p05 = analysis::weighted_quantile(r, w, 0.05);
    s.p95 = analysis::weighted_quantile(r, w, 0.95);
    s.low = low_area / nominal_area;
  }
  std::vector<analysis::ThinRegion> computed;
  if (!own) {
    Eigen::VectorXd filled = thickness;
    for (Eigen::Index f = 0; f < filled.size(); ++f)
      if (!std::isfinite(filled(f))) filled(f) = 0.0;
    computed = analysis::thin_regions(mesh, filled, limit);
    std::erase_if(computed, [&](const analysis::ThinRegion& r) {
      return r.area < analysis::kSpeckArea * spec.h0 * spec.h0;
    });
  }
  const std::vector<analysis::ThinRegion>& regions = own ? *own : computed;
  s.regions = int(regions.size());
  s.thin_flagged.assign(nfeatures, NAN);
  s.thin_regions.assign(nfeatures, 0);
  for (std::size_t k = 0; k < nfeatures; ++k) {
    if (spec.part.features[k].role != testing::WallRole::thin_feature) continue;
    s.thin_flagged[k] = feature_low[k] / std::max(feature_area[k], 1e-300);
    for (const analysis::ThinRegion& r : regions)
      for (const int f : r.face_indices)
        if (labels[std::size_t(f)].role == testing::WallRole::thin_feature &&
            labels[std::size_t(f)].feature == int(k)) {
          ++s.thin_regions[k];
          break;
        }
  }
}

Mesh to_cgal(const geometry::SurfaceMesh& m) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for (Eigen::Index i = 0; i < m.num_vertices(); ++i)
    v.push_back(mesh.add_vertex({m.vertices()(i, 0), m.vertices()(i, 1), m.vertices()(i, 2)}));
  for (Eigen::Index f = 0; f < m.num_faces(); ++f)
    mesh.add_face(v[std::size_t(m.faces()(f, 0))], v[std::size_t(m.faces()(f, 1))],
                  v[std::size_t(m.faces()(f, 2))]);
  return mesh;
}

/// The file as the peers' users would load it: read, welded and validated (bemshape's
/// reader; nothing is remeshed).
geometry::SurfaceMesh load(const std::string& file) { return geometry::prepare_mesh_file(file).mesh; }

Eigen::VectorXd run_sdf(const geometry::SurfaceMesh& m) {
  Mesh mesh = to_cgal(m);
  auto sdf = mesh.add_property_map<Mesh::Face_index, double>("f:sdf", 0.0).first;
  CGAL::sdf_values(mesh, sdf, 2.0 / 3.0 * CGAL_PI, 25, false);
  Eigen::VectorXd thickness(m.num_faces());
  Eigen::Index f = 0;
  for (Mesh::Face_index fi : mesh.faces()) thickness(f++) = sdf[fi] > 0.0 ? sdf[fi] : NAN;
  return thickness;
}

Eigen::VectorXd run_ray(const geometry::SurfaceMesh& m) {
  const Mesh mesh = to_cgal(m);
  Tree tree(faces(mesh).first, faces(mesh).second, mesh);
  tree.accelerate_distance_queries();
  const double offset = kRayOffset * m.bounding_box().diagonal();
  Eigen::VectorXd thickness(m.num_faces());
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d n = m.face_normals().row(f).transpose();
    const Eigen::Vector3d c = m.face_centroids().row(f).transpose() - offset * n;
    const Kernel::Ray_3 ray({c.x(), c.y(), c.z()}, Kernel::Vector_3(-n.x(), -n.y(), -n.z()));
    double best = NAN;
    std::vector<Tree::Intersection_and_primitive_id<Kernel::Ray_3>::Type> hits;
    tree.all_intersections(ray, std::back_inserter(hits));
    for (const auto& hit : hits)
      if (const Kernel::Point_3* p = boost::get<Kernel::Point_3>(&hit.first)) {
        const double d = std::sqrt(CGAL::squared_distance(*p, ray.source())) + offset;
        if (!(d >= best)) best = d;
      }
    thickness(f) = best;
  }
  return thickness;
}

/// The shrinking ball: the ball tangent at x (inward normal −n) of radius r, centre c = x − r n;
/// if the surface point q nearest c is closer than r (other than x itself), the ball through x
/// and q tangent at x has radius |x − q|²/(2 (x − q)·n) < r. Starts from half the ray's length.
Eigen::VectorXd run_sphere(const geometry::SurfaceMesh& m) {
  const Mesh mesh = to_cgal(m);
  Tree tree(faces(mesh).first, faces(mesh).second, mesh);
  tree.accelerate_distance_queries();
  const Eigen::VectorXd ray = run_ray(m);
  const double diagonal = m.bounding_box().diagonal();
  Eigen::VectorXd thickness(m.num_faces());
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d n = m.face_normals().row(f).transpose();
    const Eigen::Vector3d x = m.face_centroids().row(f).transpose();
    double r = std::isfinite(ray(f)) ? 0.5 * ray(f) : 0.5 * diagonal;
    for (int it = 0; it < kBallIterations; ++it) {
      const Eigen::Vector3d c = x - r * n;
      const Kernel::Point_3 q = tree.closest_point(Kernel::Point_3(c.x(), c.y(), c.z()));
      const Eigen::Vector3d y(q.x(), q.y(), q.z());
      if ((c - y).norm() >= r * (1.0 - kBallTolerance)) break;
      const Eigen::Vector3d d = x - y;
      const double along = d.dot(n);
      if (!(along > 0.0)) break;
      const double next = d.squaredNorm() / (2.0 * along);
      if (!(next < r * (1.0 - kBallTolerance))) break;
      r = next;
    }
    thickness(f) = 2.0 * r;
  }
  return thickness;
}

/// Writes bemshape's solver faces with their labels and the mid-surface search's readings.
void dump_faces(const std::string& path, const PartSpec& spec,
                const analysis::ThicknessResult& result) {
  const geometry::SurfaceMesh& mesh = result.boundary.solver_mesh;
  const std::vector<testing::WallLabel> labels = design_labels(spec, mesh);
  const analysis::WallThickness& w = result.wall;
  const bool wall = w.depth.size() == mesh.num_faces();
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) return;
  std::fprintf(out, "x,y,z,nx,ny,nz,area,role,t,thickness,mid_thickness,depth,rim_indicator,"
                    "pair_thickness\n");
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    std::fprintf(out, "%g,%g,%g,%g,%g,%g,%g,%s,%g,%g,%g,%g,%g,%g\n", mesh.face_centroids()(f, 0),
                 mesh.face_centroids()(f, 1), mesh.face_centroids()(f, 2), mesh.face_normals()(f, 0),
                 mesh.face_normals()(f, 1), mesh.face_normals()(f, 2), mesh.face_areas()(f),
                 testing::to_string(labels[std::size_t(f)].role), labels[std::size_t(f)].thickness,
                 result.thickness(f), wall ? w.mid_thickness(f) : NAN, wall ? w.depth(f) : NAN,
                 wall ? w.rim_indicator(f) : NAN, wall ? w.pair_thickness(f) : NAN);
  std::fclose(out);
}

/// One tool on one file, in this process: prints "key value" pairs on one line.
int run_tool(const std::string& tool, const std::string& name, const std::string& file,
             long min_faces) {
  const PartSpec spec = part_spec(name, false, min_faces);
  Score s;
  const auto start = std::chrono::steady_clock::now();
  if (tool == "bemshape") {
    analysis::ThicknessOptions options;
    options.solve.h0 = spec.h0;
    options.min_thickness = kCheckRatio * spec.t;
    if (spec.max_thickness > 0.0) options.max_thickness = spec.max_thickness;
    options.map_to_input = false;
    const analysis::ThicknessResult result = analysis::measure_thickness(file, options);
    s.seconds = seconds_since(start);
    score(spec, result.boundary.solver_mesh, result.thickness, &result.regions, s);
    if (const char* dump = std::getenv("BENCH_DUMP_DIR"))
      dump_faces(std::string(dump) + "/" + std::filesystem::path(file).stem().string() + ".csv",
                 spec, result);
    for (const auto& [stage, seconds] : result.times.stages()) s.stages[stage] = seconds;
    const bem::SolveReport& report = result.boundary.solution.report;
    for (const auto& [stage, seconds] : report.assembly_stages) s.stages["assembly: " + stage] = seconds;
    for (const auto& [stage, seconds] : report.solve_stages) s.stages["solve: " + stage] = seconds;
    s.stages["iterations"] = report.iterations;
    s.stages["evaluations per face"] =
        double(result.wall.evaluations) / double(std::max<Eigen::Index>(1, s.faces));
    if (spec.max_thickness > 0.0) {
      s.thick_found = 0;
      if (!result.thick_regions.empty())
        for (const auto& feature : spec.part.features)
          if (feature.role == testing::WallRole::thick_feature) {
            // The thickest face's place on the design, as the faces are labelled: on a noisy
            // copy the boss's top face lies up to the noise above the feature's box.
            const Eigen::RowVector3d thickest = result.thick_regions.front().max_location.transpose();
            const Eigen::Vector3d p =
                geometry::ClosestPointQuery(spec.part.mesh).closest_points(thickest).points.row(0).transpose();
            if ((p.array() >= feature.box.min.array() - 1e-6).all() &&
                (p.array() <= feature.box.max.array() + 1e-6).all())
              s.thick_found = 1;
          }
    }
  } else {
    const geometry::SurfaceMesh mesh = load(file);
    Eigen::VectorXd thickness;
    if (tool == "ray") thickness = run_ray(mesh);
    else if (tool == "sdf") thickness = run_sdf(mesh);
    else if (tool == "sphere") thickness = run_sphere(mesh);
    else throw InputError("unknown tool '" + tool + "'");
    s.seconds = seconds_since(start);
    score(spec, mesh, thickness, nullptr, s);
  }
  // The peak of this process image (VmHWM): the rusage the parent gets also counts, from
  // before the exec, the parent's pages this child shared when it was forked.
  std::printf("seconds %.17g faces %ld median %.17g p05 %.17g p95 %.17g low %.17g regions %d "
              "thick %d peak_mb %.17g",
              s.seconds, s.faces, s.median, s.p05, s.p95, s.low, s.regions, s.thick_found,
              double(peak_resident_bytes()) / (1024.0 * 1024.0));
  for (std::size_t k = 0; k < s.thin_flagged.size(); ++k)
    if (std::isfinite(s.thin_flagged[k]))
      std::printf(" thin%zu %.17g thin_regions%zu %d", k, s.thin_flagged[k], k, s.thin_regions[k]);
  for (const auto& [stage, value] : s.stages) {
    std::string key = stage;
    std::replace(key.begin(), key.end(), ' ', '_');
    std::printf(" stage:%s %.17g", key.c_str(), value);
  }
  std::printf("\n");
  return 0;
}

/// Runs this program with --run in a child process; parses its line; the peak resident
/// memory the child reports (VmHWM), else its resource usage.
Score run_child(const std::string& self, const std::string& tool, const std::string& name,
                const std::string& file, long min_faces, int threads) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    close(fds[0]);
    close(fds[1]);
    const std::string faces = std::to_string(min_faces), nthreads = std::to_string(threads);
    execl(self.c_str(), self.c_str(), "--threads", nthreads.c_str(), "--min-faces",
          faces.c_str(), "--run", tool.c_str(), name.c_str(), file.c_str(), nullptr);
    _exit(127);
  }
  close(fds[1]);
  std::string output;
  char buffer[4096];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) output.append(buffer, std::size_t(n));
  close(fds[0]);
  int status = 0;
  struct rusage usage {};
  wait4(pid, &status, 0, &usage);
  Score s;
  s.peak_mb = double(usage.ru_maxrss) / 1024.0;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "bench_thickness_tools: %s on %s failed (status %d)\n", tool.c_str(),
                 name.c_str(), status);
    return s;
  }
  std::istringstream in(output);
  std::string key;
  double value;
  std::map<std::string, double> fields;
  while (in >> key >> value) fields[key] = value;
  s.seconds = fields["seconds"];
  if (fields.count("peak_mb") && fields["peak_mb"] > 0.0) s.peak_mb = fields["peak_mb"];
  s.faces = long(fields["faces"]);
  s.median = fields["median"];
  s.p05 = fields["p05"];
  s.p95 = fields["p95"];
  s.low = fields["low"];
  s.regions = int(fields["regions"]);
  s.thick_found = int(fields["thick"]);
  for (const auto& [k, v] : fields) {
    if (k.rfind("thin_regions", 0) == 0) {
      const std::size_t i = std::stoul(k.substr(12));
      if (s.thin_regions.size() <= i) s.thin_regions.resize(i + 1, 0);
      s.thin_regions[i] = int(v);
    } else if (k.rfind("thin", 0) == 0) {
      const std::size_t i = std::stoul(k.substr(4));
      if (s.thin_flagged.size() <= i) s.thin_flagged.resize(i + 1, NAN);
      s.thin_flagged[i] = v;
    } else if (k.rfind("stage:", 0) == 0) {
      std::string stage = k.substr(6);
      std::replace(stage.begin(), stage.end(), '_', ' ');
      s.stages[stage] = v;
    }
  }
  return s;
}

void print_row(const std::string& part, double noise, const std::string& tool, const Score& s) {
  std::printf("%-13s %5.3f %-9s %7ld %8.2f %7.0f %7.4f %7.4f %7.4f %7.2f%%", part.c_str(), noise,
              tool.c_str(), s.faces, s.seconds, s.peak_mb, s.median, s.p05, s.p95, 100.0 * s.low);
  std::printf(" %4d", s.regions);
  for (std::size_t k = 0; k < s.thin_flagged.size(); ++k)
    if (std::isfinite(s.thin_flagged[k]))
      std::printf("  thin%zu %5.1f%% in %d", k, 100.0 * s.thin_flagged[k],
                  k < s.thin_regions.size() ? s.thin_regions[k] : 0);
  if (s.thick_found >= 0) std::printf("  boss %s", s.thick_found ? "found" : "MISSED");
  std::printf("\n");
  std::fflush(stdout);
}

void print_profile(const std::string& part, const Score& s) {
  std::printf("%-13s profile:", part.c_str());
  for (const auto& [stage, value] : s.stages) std::printf("  %s %.3g", stage.c_str(), value);
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  // A tool's run (--run, a child of this process) takes the allocator settings of the bemshape
  // executable (apps/main.cpp), so that it runs as a user's process would: 2 MB heap pages,
  // freed memory kept for reuse. Not the parent, which would only hold its freed pages longer.
  if (std::any_of(argv + 1, argv + argc, [](const char* a) { return std::strcmp(a, "--run") == 0; })) {
    bemshape::restart_with_heap_huge_pages(argv);
    bemshape::retain_freed_heap_memory();
    bemshape::pad_heap_growth();
  }
  std::vector<std::string> names, tools{"bemshape", "ray", "sdf", "sphere"};
  std::vector<double> noises;
  std::uint64_t seed = 1;
  long min_faces = testing::kFineExportFaces;
  std::string keep;
  bool profile = false;
  int threads = omp_get_max_threads();
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      const bool value = i + 1 < argc;
      if (arg == "--threads" && value) {
        threads = std::stoi(argv[++i]);
        omp_set_num_threads(threads);
      } else if (arg == "--noise" && value) {
        // The numbers that follow (a part's name ends the list).
        for (char* end = nullptr; i + 1 < argc; ++i) {
          const double noise = std::strtod(argv[i + 1], &end);
          if (end == argv[i + 1] || *end != '\0') break;
          noises.push_back(noise);
        }
      } else if (arg == "--seed" && value) {
        seed = std::stoull(argv[++i]);
      } else if (arg == "--min-faces" && value) {
        min_faces = std::stol(argv[++i]);
      } else if (arg == "--keep" && value) {
        keep = argv[++i];
      } else if (arg == "--profile") {
        profile = true;
      } else if (arg == "--tools" && value) {
        tools.clear();
        std::stringstream list(argv[++i]);
        for (std::string t; std::getline(list, t, ',');) tools.push_back(t);
      } else if (arg == "--run" && i + 3 < argc) {
        return run_tool(argv[i + 1], argv[i + 2], argv[i + 3], min_faces);
      } else if (!arg.empty() && arg[0] == '-') {
        std::fprintf(stderr,
                     "usage: bench_thickness_tools [--threads N] [--noise F ...] [--seed S] "
                     "[--tools bemshape,ray,sdf,sphere] [--min-faces N] [--keep DIR] "
                     "[--profile] [PART ...]\n");
        return 2;
      } else {
        names.push_back(arg);
      }
    }
    if (noises.empty()) noises.push_back(0.0);
    if (names.empty()) {
      names = testing::labelled_part_names();
      names.erase(std::remove(names.begin(), names.end(), "large-tray"), names.end());
      names.push_back("plate_holes");
    }
    const std::string self = std::filesystem::canonical("/proc/self/exe").string();
    const std::filesystem::path dir =
        keep.empty() ? std::filesystem::temp_directory_path() /
                           ("bench_thickness_tools." + std::to_string(getpid()))
                     : std::filesystem::path(keep);
    std::filesystem::create_directories(dir);
    std::printf("bench_thickness_tools: %d threads, fine exports of at least %ld faces, seed %llu; "
                "bemshape with --min-thickness 0.9t (h0 = 0.9t) and defaults\n",
                threads, min_faces, (unsigned long long)seed);
    std::printf("%-13s %5s %-9s %7s %8s %7s %7s %7s %7s %8s %4s  thin features\n", "part",
                "noise", "tool", "faces", "time[s]", "peak[MB]", "median", "p05", "p95", "<0.9t",
                "reg");
    for (const std::string& name : names) {
      const PartSpec spec = part_spec(name, true, min_faces);
      for (const double noise : noises) {
        const geometry::SurfaceMesh mesh =
            noise > 0.0 ? testing::with_normal_noise(spec.part.mesh, noise * spec.t, seed)
                        : spec.part.mesh;
        char suffix[32];
        std::snprintf(suffix, sizeof suffix, "-%.3f.stl", noise);
        const std::string file = (dir / (name + suffix)).string();
        output::write_binary_stl(file, mesh.vertices(), mesh.faces());
        for (const std::string& tool : tools) {
          const Score s = run_child(self, tool, name, file, min_faces, threads);
          print_row(name, noise, tool, s);
          if (profile && tool == "bemshape") print_profile(name, s);
        }
        if (keep.empty()) std::filesystem::remove(file);
      }
    }
    if (keep.empty()) std::filesystem::remove(dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_thickness_tools: %s\n", e.what());
    return 1;
  }
  return 0;
}
