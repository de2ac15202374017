// Damaged copies of a bundled part, made by code, through the real `bemshape check` and
// through the thickness pipeline (analysis::measure_thickness on the same file): each defect
// is repaired (exit 0, the repair listed with where it was made and how large it was, at the
// damage and at most the repair length ℓ across), and away from the repair the thickness is
// the intact part's within 1 %.
//
// The part is tests/data/meshes/unit_sphere.STL (1280 facets, edges about 0.1; ℓ = 2 % of the
// bounding-box diagonal = 0.069). The intact copy has its topmost facet ABC split into a
// small inner triangle abc (ABC shrunk by kInnerScale towards its centroid p, about 0.03
// across) and the ring of six triangles around it, the same surface, so that defects at p
// are small against ℓ:
//
//   hole               abc removed: a hole of 3 edges;
//   non-manifold       abc duplicated, and a fin (one triangle) on its edge ab standing out
//                      of the surface: edges shared by 4 and 3 faces;
//   overlapping        a cube of side 0.02 centred at p, half inside the sphere: two bodies
//                      with a few crossing face pairs, united with a bump of 0.01.
//
// Every facet edge of the sphere is a crease the remesher keeps (default sharp angle 1°), and
// the element size is above the facets' edges, so the solver mesh is the input mesh except
// inside the facet that was damaged: away from the repair the two runs solve on the same
// faces, and any difference there is the repair's doing. The thickness (h_p per solver face)
// of the damaged run is compared with the intact run's on the face under its centroid.
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/measure_thickness.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/mesh_io.hpp"
#include "tests/apps/bemshape_runner.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

/// abc = ABC scaled by this about its centroid: about 0.03 across, half of ℓ.
constexpr double kInnerScale = 0.3;
/// The cube of the overlapping case: side 0.02, inside the facet (inradius about 0.03).
constexpr double kCubeSide = 0.02;
/// h0 a quarter of the radius, so that "a few h0 away from the repair" leaves most of the
/// sphere; the element size is above every facet edge (≤ 0.13), so the remesher keeps the
/// facets (1280 solver faces, about 5 s per solve on two cores).
constexpr double kH0 = 0.25;
constexpr double kMaxEdge = 0.2;
/// Faces closer than this many h0 to the repair are not compared. The interior (Yukawa)
/// solution decays like exp(−κ r), κ = 2/(a·h0) = 10/h0: a change at the repair is e^{−30}
/// of itself at 3·h0.
constexpr double kFarFromRepair = 3.0;
/// The acceptance criterion: the thickness away from a repair within 1 % of the intact part's.
constexpr double kSameThickness = 0.01;

struct Surface {
  Eigen::MatrixX3d vertices;
  std::vector<Eigen::Vector3i> faces;

  int add_vertex(const Eigen::Vector3d& x) {
    vertices.conservativeResize(vertices.rows() + 1, 3);
    vertices.row(vertices.rows() - 1) = x.transpose();
    return static_cast<int>(vertices.rows() - 1);
  }
  Eigen::Vector3d vertex(int v) const { return vertices.row(v).transpose(); }
  void add_body(const geometry::SurfaceMesh& body) {
    const int offset = static_cast<int>(vertices.rows());
    for (Eigen::Index v = 0; v < body.num_vertices(); ++v)
      add_vertex(body.vertices().row(v).transpose());
    for (Eigen::Index f = 0; f < body.num_faces(); ++f)
      faces.push_back(body.faces().row(f).transpose().array() + offset);
  }
  void write(const std::string& path) const {
    Eigen::MatrixX3i F(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f)
      F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
    geometry::write_binary_stl(path, vertices, F);
  }
};

/// The sphere with its topmost facet split around the inner triangle abc (the last face, so
/// that the damaged copies can remove or duplicate it); `site` = the facet's centroid p,
/// `normal` its outward unit normal.
struct IntactSphere {
  Surface surface;
  Eigen::Vector3d site, normal;
  int a = -1, b = -1, c = -1;
};

IntactSphere intact_sphere() {
  const geometry::TriangleSoup soup =
      geometry::read_triangle_soup(std::string(BEMSHAPE_TEST_DATA_DIR) + "/meshes/unit_sphere.STL");
  IntactSphere t;
  t.surface.vertices = soup.vertices;
  const auto centroid = [&](Eigen::Index f) -> Eigen::Vector3d {
    return (soup.vertices.row(soup.faces(f, 0)) + soup.vertices.row(soup.faces(f, 1)) +
            soup.vertices.row(soup.faces(f, 2)))
               .transpose() /
           3.0;
  };
  Eigen::Index top = 0;
  for (Eigen::Index f = 1; f < soup.faces.rows(); ++f)
    if (centroid(f).z() > centroid(top).z()) top = f;
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f)
    if (f != top) t.surface.faces.push_back(soup.faces.row(f).transpose());
  const Eigen::Vector3i ABC = soup.faces.row(top).transpose();
  const Eigen::Vector3d A = t.surface.vertex(ABC(0)), B = t.surface.vertex(ABC(1)),
                        C = t.surface.vertex(ABC(2));
  t.site = centroid(top);
  t.normal = (B - A).cross(C - A).normalized();
  REQUIRE(t.normal.dot(t.site) > 0.0);  // the file's facets face outward
  t.a = t.surface.add_vertex(t.site + kInnerScale * (A - t.site));
  t.b = t.surface.add_vertex(t.site + kInnerScale * (B - t.site));
  t.c = t.surface.add_vertex(t.site + kInnerScale * (C - t.site));
  // The ring A B b a, B C c b, C A a c, each quad as two triangles oriented as ABC.
  for (const auto& [outer0, outer1, inner1, inner0] :
       {std::array{ABC(0), ABC(1), t.b, t.a}, std::array{ABC(1), ABC(2), t.c, t.b},
        std::array{ABC(2), ABC(0), t.a, t.c}}) {
    t.surface.faces.emplace_back(outer0, outer1, inner1);
    t.surface.faces.emplace_back(outer0, inner1, inner0);
  }
  t.surface.faces.emplace_back(t.a, t.b, t.c);
  return t;
}

/// The repair lines of a check report ("  - ..." under "repairs:").
std::vector<std::string> repair_lines(const std::string& report) {
  std::vector<std::string> lines;
  const auto begin = report.find("\nrepairs:\n");
  if (begin == std::string::npos) return lines;
  std::istringstream in(report.substr(begin + 10));
  for (std::string line; std::getline(in, line) && line.rfind("  - ", 0) == 0;)
    lines.push_back(line);
  return lines;
}

/// Every "(x, y, z)" and "(first at x, y, z)" of a line.
std::vector<Eigen::Vector3d> points_in(const std::string& line) {
  static const std::regex point(R"(\((?:first at )?([-0-9.e+]+), ([-0-9.e+]+), ([-0-9.e+]+)\))");
  std::vector<Eigen::Vector3d> points;
  for (auto it = std::sregex_iterator(line.begin(), line.end(), point);
       it != std::sregex_iterator(); ++it)
    points.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]));
  return points;
}

/// The number before " across" in a line, or NaN.
double size_in(const std::string& line) {
  static const std::regex across(R"(([0-9.e+-]+) across)");
  std::smatch m;
  return std::regex_search(line, m, across) ? std::stod(m[1]) : std::nan("");
}

analysis::ThicknessResult thickness_of(const std::string& file) {
  analysis::ThicknessOptions options;
  options.solve.h0 = kH0;
  options.solve.max_edge = kMaxEdge;
  options.map_to_input = false;
  return analysis::measure_thickness(file, options);
}

struct FarDifference {
  double largest = 0.0;  ///< max |h − h_intact| / h_intact over the faces compared
  int compared = 0;
};

/// Each solver face of `result` farther than kFarFromRepair·h0 from `site` against the
/// intact run's solver face under its centroid.
FarDifference far_thickness_difference(const analysis::ThicknessResult& result,
                                       const analysis::ThicknessResult& intact,
                                       const Eigen::Vector3d& site) {
  const geometry::SurfaceMesh& mesh = result.boundary.solver_mesh;
  const geometry::ClosestPointQuery on_intact(intact.boundary.solver_mesh);
  FarDifference d;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d x = mesh.face_centroids().row(f).transpose();
    if ((x - site).norm() <= kFarFromRepair * kH0) continue;
    const double reference = intact.thickness(on_intact.closest(x).face);
    d.largest = std::max(d.largest, std::abs(result.thickness(f) - reference) / reference);
    ++d.compared;
  }
  return d;
}

}  // namespace

TEST_CASE(
    "a small hole, non-manifold edges and overlapping bodies on the sphere are repaired "
    "where they are, and the thickness a few h0 away is the intact part's within 1 %") {
  const IntactSphere intact = intact_sphere();
  const double repair_length = 0.02 * (intact.surface.vertices.colwise().maxCoeff() -
                                       intact.surface.vertices.colwise().minCoeff())
                                          .norm();
  const std::string intact_file = (scratch_folder() / "sphere_intact.stl").string();
  intact.surface.write(intact_file);
  const analysis::ThicknessResult reference = thickness_of(intact_file);
  // Only the STL reader's merge of equal corners: the intact copy needs no repair.
  CHECK(reference.input.report.repairs.size() == 1);

  struct Damage {
    std::string name;
    Surface surface;
    std::vector<std::string> repairs;  // what the report must list
    std::string sized;                 // the repair that must say how large it was
  };
  std::vector<Damage> damages;
  {
    Damage hole{"hole", intact.surface, {"filled a hole of 3 edges"}, "filled a hole"};
    hole.surface.faces.pop_back();
    damages.push_back(hole);
  }
  {
    Damage fin{"nonmanifold",
               intact.surface,
               {"removed 1 duplicate face (first at", "split 1 non-manifold edge",
                "duplicated 2 vertices shared by separate fans",
                "removed a loose open piece of 1 face"},
               "removed a loose open piece"};
    const Eigen::Vector3d a = intact.surface.vertex(intact.a), b = intact.surface.vertex(intact.b);
    const int q = fin.surface.add_vertex(0.5 * (a + b) + 0.5 * (b - a).norm() * intact.normal);
    fin.surface.faces.push_back(fin.surface.faces.back());
    fin.surface.faces.emplace_back(intact.b, intact.a, q);
    damages.push_back(fin);
  }
  {
    Damage overlap{"overlapping", intact.surface, {"united 2 overlapping bodies"}, "united"};
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(kCubeSide / 2);
    overlap.surface.add_body(geometry::make_box_solid(intact.site - half, intact.site + half));
    damages.push_back(overlap);
  }

  for (const Damage& damage : damages) {
    CAPTURE(damage.name);
    const std::string file = (scratch_folder() / ("sphere_" + damage.name + ".stl")).string();
    damage.surface.write(file);
    const Run r = run_bemshape("check '" + file + "'");
    CAPTURE(r.out, r.err);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("result: usable"));
    for (const std::string& repair : damage.repairs) CHECK_THAT(r.out, Catch::Contains(repair));
    // Every repair but the reader's merge says where it was made: at the damage.
    const std::vector<std::string> lines = repair_lines(r.out);
    CHECK(lines.size() == damage.repairs.size() + 1);  // and the STL reader's merge
    int sized = 0;
    for (std::size_t i = 1; i < lines.size(); ++i) {
      CAPTURE(lines[i]);
      const std::vector<Eigen::Vector3d> at = points_in(lines[i]);
      CHECK(!at.empty());
      for (const Eigen::Vector3d& x : at) CHECK((x - intact.site).norm() < repair_length);
      if (lines[i].find(damage.sized) != std::string::npos) {
        ++sized;
        const double size = size_in(lines[i]);
        CHECK(size > 0.0);
        CHECK(size <= repair_length);
      }
    }
    CHECK(sized == 1);

    const analysis::ThicknessResult repaired = thickness_of(file);
    const FarDifference d = far_thickness_difference(repaired, reference, intact.site);
    CAPTURE(d.largest, d.compared, repaired.boundary.solver_mesh.num_faces());
    CHECK(d.compared > repaired.boundary.solver_mesh.num_faces() / 2);
    CHECK(d.largest < kSameThickness);
  }
}
