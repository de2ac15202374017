// The wall thickness of the labelled parts (tests/support/labelled_parts.hpp) against their design,
// scored the way a designer judges a minimum-wall-thickness check: the table of
// docs/validation.md, "Wall thickness on parts with known walls".
//
//   bench_wall_thickness [--measure wall|sphere|paper] [--max-edge E] [--threads N]
//                        [--dump PREFIX] [PART ...]
// (--dump writes PREFIX<part>.csv: every solver face with its label and the search's readings.)
//
// Without parts: every labelled part but large-tray (its uniform default mesh has millions of
// faces; bench_thickness_tools measures it on the graded mesh). Each part is given to analysis::measure_thickness as its
// triangles (the part's own CAD-like mesh, welded and validated as a file would be) with
// h0 = --min-thickness = 0.9·t (t its nominal wall), as `bemshape thickness part.stl
// --min-thickness 0.9t` runs, and the defaults otherwise. Per part, over the solver faces
// labelled by the part's classifier (area-weighted, reading/design):
//
//   nominal  median, p05, p95 of the nominal walls' readings (design: the local wall, so a
//            taper's every face is compared with its own wall), and the share of their area
//            read below 0.9 of their design ("low %": a nominal wall the check flags);
//   rims     median of the rim faces (end faces and hole walls: design = the wall they close);
//   check    the check at 0.9·t: PASS/FAIL and the number of regions;
//   thin     per thin feature: the share of its area read below 0.9·t (flagged), whether one
//            thin region has its minimum inside the feature's box (located);
//   1.1t     the share of the nominal walls' area a check at 1.1·t flags;
//   thick    with --max-thickness 1.5·t: the thick regions and whether the first one's maximum
//            lies in a thick feature's box;
//   time     of the measure_thickness call [s].

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/measure_thickness.hpp"
#include "analysis/input_mesh.hpp"
#include "analysis/thickness_statistics.hpp"
#include "core/errors.hpp"
#include "tests/support/labelled_parts.hpp"

using namespace bemshape;

namespace {

struct Options {
  std::string measure = "wall";
  double max_edge = 0.0;  // 0: the default rule
  std::string dump;       // prefix of the per-face CSV files; empty: none
  std::vector<std::string> parts;
};

bool inside(const geometry::BoundingBox& box, const Eigen::Vector3d& x, double margin) {
  return (x.array() >= box.min.array() - margin).all() &&
         (x.array() <= box.max.array() + margin).all();
}

/// Area-weighted p-quantile of `ratios` over the faces in `faces`.
double quantile(const std::vector<double>& ratios, const std::vector<double>& areas, double p) {
  if (ratios.empty())
    return std::nan("");
  return analysis::weighted_quantile(Eigen::Map<const Eigen::VectorXd>(ratios.data(), Eigen::Index(ratios.size())),
                                     Eigen::Map<const Eigen::VectorXd>(areas.data(), Eigen::Index(areas.size())), p);
}

void run_part(const std::string& name, const Options& options) {
  const testing::LabelledPart part = testing::make_labelled_part(name);
  const double t = part.nominal_wall;
  const geometry::PreparedMesh input = analysis::prepare_triangles(
      part.mesh.vertices(), part.mesh.faces(), name);

  analysis::ThicknessOptions job;
  job.solve.h0 = 0.9 * t;
  job.solve.a = 0.2;
  if (options.max_edge > 0.0)
    job.solve.max_edge = options.max_edge;
  job.measure = analysis::thickness_measure(options.measure);
  job.min_thickness = 0.9 * t;
  job.max_thickness = 1.5 * t;
  job.map_to_input = false;
  const auto start = std::chrono::steady_clock::now();
  const analysis::ThicknessResult result = analysis::measure_thickness(input, job);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const geometry::SurfaceMesh& mesh = result.boundary.solver_mesh;
  const std::vector<testing::WallLabel> labels = part.label_faces(mesh);
  std::vector<double> nominal, nominal_area, rim, rim_area;
  double low_area = 0.0, total_nominal = 0.0, flagged_at_11 = 0.0, worst_t = 0.0;
  Eigen::Index worst_low = -1;  // the nominal face read lowest against its wall
  std::vector<double> feature_area(part.features.size(), 0.0),
      feature_flagged(part.features.size(), 0.0);
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    const testing::WallLabel& l = labels[std::size_t(f)];
    const double area = mesh.face_areas()(f), value = result.thickness(f);
    switch (l.role) {
      case testing::WallRole::nominal:
        nominal.push_back(value / l.thickness);
        nominal_area.push_back(area);
        total_nominal += area;
        if (value < 0.9 * l.thickness) {
          low_area += area;
          if (worst_low < 0 || value / l.thickness < result.thickness(worst_low) / worst_t) {
            worst_low = f;
            worst_t = l.thickness;
          }
        }
        if (value < 1.1 * l.thickness)
          flagged_at_11 += area;
        break;
      case testing::WallRole::rim:
        rim.push_back(value / l.thickness);
        rim_area.push_back(area);
        break;
      case testing::WallRole::thin_feature:
        feature_area[std::size_t(l.feature)] += area;
        if (value < 0.9 * t)
          feature_flagged[std::size_t(l.feature)] += area;
        break;
      default:
        break;
    }
  }
  std::printf("%-13s t %-4g faces %7ld  nominal median %.4f p05 %.4f p95 %.4f low %.2f %%  "
              "rims median %.4f  check %s (%zu regions)  1.1t flags %.1f %%  time %.1f s\n",
              name.c_str(), t, long(mesh.num_faces()), quantile(nominal, nominal_area, 0.5),
              quantile(nominal, nominal_area, 0.05), quantile(nominal, nominal_area, 0.95),
              100.0 * low_area / std::max(total_nominal, 1e-300),
              quantile(rim, rim_area, 0.5), result.regions.empty() ? "PASS" : "FAIL",
              result.regions.size(), 100.0 * flagged_at_11 / std::max(total_nominal, 1e-300),
              seconds);
  if (worst_low >= 0) {
    const Eigen::Vector3d x = mesh.face_centroids().row(worst_low).transpose();
    std::printf("    nominal faces below 0.9 t: the lowest reads %.4f t at (%.2f, %.2f, %.2f)\n",
                result.thickness(worst_low) / worst_t, x.x(), x.y(), x.z());
  }
  if (!options.dump.empty()) {
    // One row per solver face: where it is, its label and every reading of the search.
    std::FILE* out = std::fopen((options.dump + name + ".csv").c_str(), "w");
    if (out) {
      std::fprintf(out, "x,y,z,nx,ny,nz,role,t,thickness,mid_thickness,depth,rim_indicator,"
                        "pair_thickness\n");
      const analysis::WallThickness& w = result.wall;
      const bool wall = w.depth.size() == mesh.num_faces();
      for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
        const auto& l = labels[std::size_t(f)];
        std::fprintf(out, "%g,%g,%g,%g,%g,%g,%s,%g,%g,%g,%g,%g,%g\n", mesh.face_centroids()(f, 0),
                     mesh.face_centroids()(f, 1), mesh.face_centroids()(f, 2),
                     mesh.face_normals()(f, 0), mesh.face_normals()(f, 1),
                     mesh.face_normals()(f, 2), testing::to_string(l.role), l.thickness,
                     result.thickness(f), wall ? w.mid_thickness(f) : NAN,
                     wall ? w.depth(f) : NAN, wall ? w.rim_indicator(f) : NAN,
                     wall ? w.pair_thickness(f) : NAN);
      }
      std::fclose(out);
    }
  }
  // Every thin region: what its minimum is, where, and the role of the face that holds it
  // (a region on a part's nominal walls or rims is a false alarm).
  for (const analysis::ThinRegion& r : result.regions) {
    Eigen::Index at = r.face_indices.empty() ? -1 : r.face_indices.front();
    for (const int f : r.face_indices)
      if (result.thickness(f) < result.thickness(at)) at = f;
    const testing::WallLabel& l = labels[std::size_t(at)];
    std::printf("    region  min %.3f at (%.2f, %.2f, %.2f) on a %s face (t %g), area %.2f, "
                "%zu faces\n",
                r.minimum, r.min_location.x(), r.min_location.y(), r.min_location.z(),
                testing::to_string(l.role), l.thickness, r.area,
                r.face_indices.size());
  }
  for (std::size_t k = 0; k < part.features.size(); ++k) {
    const testing::PartFeature& feature = part.features[k];
    if (feature.role == testing::WallRole::thin_feature) {
      // The region holding most of the feature's area: its share of the feature, where its
      // minimum and centroid are.
      const analysis::ThinRegion* best = nullptr;
      double best_area = 0.0;
      for (const analysis::ThinRegion& r : result.regions) {
        double area = 0.0;
        for (const int f : r.face_indices)
          if (labels[std::size_t(f)].role == testing::WallRole::thin_feature &&
              labels[std::size_t(f)].feature == int(k))
            area += mesh.face_areas()(f);
        if (area > best_area) {
          best_area = area;
          best = &r;
        }
      }
      std::printf("    thin feature %-24s %g: flagged %.1f %% of its area, %.1f %% in one region "
                  "(of %zu), its minimum %.3f %s the feature, its centroid %s\n",
                  feature.name.c_str(), feature.thickness,
                  100.0 * feature_flagged[k] / std::max(feature_area[k], 1e-300),
                  100.0 * best_area / std::max(feature_area[k], 1e-300), result.regions.size(),
                  best ? best->minimum : std::nan(""),
                  best && inside(feature.box, best->min_location, 1e-6 * t) ? "inside"
                                                                            : "NOT inside",
                  best && inside(feature.box, best->centroid, 1e-6 * t) ? "inside" : "NOT inside");
    } else {
      const bool found = !result.thick_regions.empty() &&
                         inside(feature.box, result.thick_regions.front().max_location, 1e-6 * t);
      std::printf("    thick feature %-23s %g: %zu thick regions above %g, the thickest (max %.3f) "
                  "%s it\n",
                  feature.name.c_str(), feature.thickness, result.thick_regions.size(), 1.5 * t,
                  result.thick_regions.empty() ? 0.0 : result.thick_regions.front().maximum,
                  found ? "inside" : "NOT inside");
    }
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--measure" && i + 1 < argc) {
      options.measure = argv[++i];
    } else if (arg == "--dump" && i + 1 < argc) {
      options.dump = argv[++i];
    } else if (arg == "--max-edge" && i + 1 < argc) {
      options.max_edge = std::stod(argv[++i]);
    } else if (arg == "--threads" && i + 1 < argc) {
      omp_set_num_threads(std::stoi(argv[++i]));
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr,
                   "usage: bench_wall_thickness [--measure wall|sphere|paper] [--max-edge E] "
                   "[--threads N] [--dump PREFIX] [PART ...]\n");
      return 2;
    } else {
      options.parts.push_back(arg);
    }
  }
  if (options.parts.empty())
    for (const std::string& name : testing::labelled_part_names())
      if (name != "large-tray")  // millions of faces at the uniform default mesh
        options.parts.push_back(name);
  std::printf("bench_wall_thickness: measure %s, h0 = --min-thickness = 0.9 t, %d threads\n",
              options.measure.c_str(), omp_get_max_threads());
  try {
    for (const std::string& name : options.parts)
      run_part(name, options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_wall_thickness: %s\n", e.what());
    return 2;
  }
  return 0;
}
