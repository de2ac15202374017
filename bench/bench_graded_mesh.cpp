// bench_graded_mesh: the uniform default solver mesh against the graded one (issue #32), per
// part: faces, time, edge range, smallest angle, how far the surface moved.
//
//   bench_graded_mesh [OPTIONS] [PART ...]
//
// PART is a labelled part (tests/support/labelled_parts.hpp; h0 = 0.9 × its nominal wall, read as
// its STL export would be: welded, validated, repaired) or
// FILE:H0 (a mesh file and its h0). Without parts: every labelled part and
// tests/data/meshes/plate_holes.STL at h0 = 0.9 × 12.7.
//
// Options (defaults: geometry::GradedMeshParameters):
//   --max-edge-ratio R    h_max = R·h0
//   --gradation G
//   --smooth-angle D      θ_s [degrees] (0: keep every crease)
//   --chord C             δ = C·h0
//   --no-uniform          skip the uniform mesh (geometry::refine_uniformly)
//   --uniform-edge E      edge of the uniform mesh as a multiple of h0 (default 0.3 = 1.5·a·h0)
//   --write DIR           write each mesh as DIR/<part>-uniform.stl and DIR/<part>-graded.stl
//   --wall-reading        start from the wall reading's default mesh
//                         (analysis::wall_reading_mesh_parameters) instead of issue #32's
//   --thickness-ratio C   c_t; --thin-wall-ratio T: t_thin = T·h0; --curvature-ratio C: c_ρ
//
// One line per mesh:
//   part kind faces seconds min_edge max_edge min_angle max_edge/h volume_change area_change
//   max_distance/diagonal, then the graded mesh's area by size reason.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "apps/output/stl_writer.hpp"
#include "bem/kernels/transmission_parameters.hpp"
#include "core/errors.hpp"
#include "analysis/boundary_solve.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/graded_remeshing.hpp"
#include "geometry/isotropic_remeshing.hpp"
#include "tests/support/labelled_parts.hpp"
#include "geometry/mesh_preparation.hpp"

namespace {

using namespace bemshape;

struct Part {
  std::string name;
  geometry::SurfaceMesh mesh;
  double h0 = 0.0;
};

/// Distance from p to the triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5:
/// the Voronoi region of p, no division by a small area).
double triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  // Inside: the distance to the plane.
  const Eigen::Vector3d n = ab.cross(ac);
  return std::abs(ap.dot(n)) / n.norm();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double min_edge(const geometry::SurfaceMesh& m) {
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      smallest = std::min(smallest, (m.corner(f, (k + 1) % 3) - m.corner(f, k)).norm());
  return smallest;
}

void print_line(const Part& part, const std::string& kind, const geometry::SurfaceMesh& m,
                double seconds, double max_ratio) {
  const double diagonal = part.mesh.bounding_box().diagonal();
  Eigen::Index worst = 0;
  const double distance =
      geometry::ClosestPointQuery(part.mesh).closest_points(m.vertices()).distances.maxCoeff(&worst);
  if (std::getenv("BENCH_DEBUG")) {
    double brute = 1e300;
    const Eigen::Vector3d p = m.vertices().row(worst);
    for (Eigen::Index f = 0; f < part.mesh.num_faces(); ++f)
      brute = std::min(brute, triangle_distance(p, part.mesh.corner(f, 0), part.mesh.corner(f, 1), part.mesh.corner(f, 2)));
    std::printf("brute force distance %.3e\n", brute);
  }
  if (std::getenv("BENCH_DEBUG"))
    std::printf("worst vertex %ld at %.9g %.9g %.9g\n", long(worst), m.vertices()(worst, 0),
                m.vertices()(worst, 1), m.vertices()(worst, 2));
  std::printf("%-14s %-8s faces %8ld  %7.2f s  edge %.3g..%.3g  min angle %5.1f  max edge/h %.2f  "
              "volume %+.2e  area %+.2e  distance %.1e\n",
              part.name.c_str(), kind.c_str(), static_cast<long>(m.num_faces()), seconds, min_edge(m),
              m.max_edge_length(), m.smallest_angle_degrees(), max_ratio,
              m.signed_volume() / part.mesh.signed_volume() - 1.0, m.area() / part.mesh.area() - 1.0,
              distance / diagonal);
}

/// A labelled part as the program would read its STL export: welded, validated, repaired.
Part labelled_part(const std::string& name) {
  const testing::LabelledPart part = testing::make_labelled_part(name);
  geometry::TriangleSoup soup;
  soup.vertices = part.mesh.vertices();
  soup.faces = part.mesh.faces();
  soup.format = "labelled part";
  geometry::PreparedMesh prepared = geometry::inspect_triangle_soup(soup, name);
  if (!prepared.report.usable())
    throw InputError(prepared.report.refusal_message());
  return {part.name, std::move(prepared.mesh), 0.9 * part.nominal_wall};
}

}  // namespace

int main(int argc, char** argv) {
  geometry::GradedMeshParameters graded;
  bool uniform = true;
  double uniform_edge_ratio = -1.0;
  std::string write_dir;
  std::vector<Part> parts;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << arg << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--wall-reading")  // the default mesh of the wall reading; later options change it
      graded = analysis::wall_reading_mesh_parameters(1.0, 0.2, std::nullopt);
    else if (arg == "--thickness-ratio")
      graded.wall_thickness_ratio = std::stod(value());
    else if (arg == "--thin-wall-ratio")
      graded.thin_wall_ratio = std::stod(value());
    else if (arg == "--crease-angle")
      graded.crease_angle_degrees = std::stod(value());
    else if (arg == "--normal-scale")
      graded.normal_scale_ratio = std::stod(value());
    else if (arg == "--chord-wall-ratio")
      graded.chord_thickness_ratio = std::stod(value());
    else if (arg == "--min-chord-ratio")
      graded.min_chord_ratio = std::stod(value());
    else if (arg == "--min-size-ratio")
      graded.min_size_ratio = std::stod(value());
    else if (arg == "--curvature-ratio")
      graded.curvature_ratio = std::stod(value());
    else if (arg == "--max-edge-ratio")
      graded.max_edge_ratio = std::stod(value());
    else if (arg == "--gradation")
      graded.gradation = std::stod(value());
    else if (arg == "--smooth-angle")
      graded.smooth_angle_degrees = std::stod(value());
    else if (arg == "--chord")
      graded.chord_tolerance_ratio = std::stod(value());
    else if (arg == "--no-uniform")
      uniform = false;
    else if (arg == "--uniform-edge")
      uniform_edge_ratio = std::stod(value());
    else if (arg == "--write")
      write_dir = value();
    else if (const auto colon = arg.rfind(':'); colon != std::string::npos) {
      const std::string file = arg.substr(0, colon);
      parts.push_back({std::filesystem::path(file).stem().string(),
                       geometry::prepare_mesh_file(file).mesh, std::stod(arg.substr(colon + 1))});
    } else {
      parts.push_back(labelled_part(arg));
    }
  }
  if (parts.empty()) {
    for (const std::string& name : testing::labelled_part_names())
      parts.push_back(labelled_part(name));
    parts.push_back({"plate_holes.STL",
                     geometry::prepare_mesh_file(BEMSHAPE_TEST_DATA_DIR "/meshes/plate_holes.STL").mesh,
                     0.9 * 12.7});
  }

  for (const Part& part : parts) {
    const double fine = bem::TransmissionParameters::from_shape(part.h0, 0.2).default_max_edge();
    const double uniform_edge = uniform_edge_ratio > 0.0 ? uniform_edge_ratio * part.h0 : fine;
    std::printf("%-14s input faces %ld, h0 %.3g, default edge %.3g\n", part.name.c_str(),
                static_cast<long>(part.mesh.num_faces()), part.h0, fine);
    auto write = [&](const std::string& kind, const geometry::SurfaceMesh& m) {
      if (!write_dir.empty())
        output::write_binary_stl(write_dir + "/" + part.name + "-" + kind + ".stl", m.vertices(),
                                 m.faces());
    };
    if (uniform) {
      const auto start = std::chrono::steady_clock::now();
      geometry::SurfaceMesh m;
      double ratio = 0.0;
      try {
        geometry::GradedMesh g = geometry::refine_uniformly(part.mesh, uniform_edge);
        m = std::move(g.mesh);
        ratio = g.report.max_edge_ratio;
        print_line(part, "uniform", m, seconds_since(start), ratio);
        write("uniform", m);
      } catch (const std::exception& e) {
        std::printf("%-14s uniform  failed: %s\n", part.name.c_str(), e.what());
      }
    }
    geometry::GradedMeshParameters p = graded;
    p.h0 = part.h0;
    p.fine_edge = fine;
    const auto start = std::chrono::steady_clock::now();
    try {
      const geometry::GradedMesh g = geometry::graded_solver_mesh(part.mesh, p);
      print_line(part, "graded", g.mesh, seconds_since(start), g.report.max_edge_ratio);
      write("graded", g.mesh);
      std::printf("%-14s          creases %d, smoothed %d, splits %ld, collapses %ld, flips %ld, "
                  "moves %ld; area by reason:",
                  part.name.c_str(), g.report.creases, g.report.smoothed_edges, g.report.splits,
                  g.report.collapses, g.report.flips, g.report.moves);
      for (int r = 0; r < geometry::kSizeReasons; ++r)
        if (g.report.area_by_reason[static_cast<std::size_t>(r)] > 0.0)
          std::printf(" %s %.1f%%", geometry::to_string(static_cast<geometry::SizeReason>(r)),
                      100.0 * g.report.area_by_reason[static_cast<std::size_t>(r)] / g.mesh.area());
      std::printf("\n");
    } catch (const std::exception& e) {
      std::printf("%-14s graded   failed: %s\n", part.name.c_str(), e.what());
    }
    std::fflush(stdout);
  }
  return 0;
}
