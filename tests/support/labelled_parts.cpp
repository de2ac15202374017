#include "tests/support/labelled_parts.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/errors.hpp"
#include "geometry/constructive_solids.hpp"

namespace bemshape::testing {

using namespace bemshape::geometry;
namespace {

/// Positions on a labelled surface are exact up to rounding and remeshing: points within
/// this distance [mm] of a plane or a circle count as on it.
constexpr double kOn = 1e-3;
constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

using Vec3 = Eigen::Vector3d;

WallLabel nominal(double t) { return {WallRole::nominal, t, -1}; }
WallLabel rim(double t) { return {WallRole::rim, t, -1}; }
WallLabel junction() { return {WallRole::junction, kUndefined, -1}; }
WallLabel feature(const std::vector<PartFeature>& features, int k) {
  return {features[static_cast<std::size_t>(k)].role, features[static_cast<std::size_t>(k)].thickness,
          k};
}

BoundingBox box(const Vec3& lo, const Vec3& hi) { return {lo, hi}; }

/// A profile drawn in the world (x, z) plane (its polygon's y is the world z), extruded over
/// y ∈ [y_min, y_max].
SurfaceMesh profile_extrusion(const Polygon2& profile, double y_min, double y_max) {
  const SurfaceMesh prism = extrude_polygon(profile, 0.0, y_max - y_min);
  Eigen::Affine3d motion = Eigen::Affine3d::Identity();
  motion.translate(Vec3(0.0, y_max, 0.0));
  motion.rotate(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()));
  return transformed(prism, motion);
}

/// Appends the arc of radius r about c from angle a0 to a1 [rad] (both ends included) in
/// `segments` steps.
void append_arc(std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& c, double r,
                double a0, double a1, int segments) {
  for (int i = 0; i <= segments; ++i) {
    const double a = a0 + (a1 - a0) * i / segments;
    points.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
  }
}

Polygon2 to_polygon(const std::vector<Eigen::Vector2d>& points) {
  Polygon2 p(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i) p.row(static_cast<Eigen::Index>(i)) = points[i];
  return p;
}

bool near(double a, double b) { return std::abs(a - b) <= kOn; }

// ---- the parts ---------------------------------------------------------------------------

LabelledPart plate_with_holes(int segments) {
  LabelledPart part;
  part.name = "plate-holes";
  part.description = "plate 120 x 80 x 4 with four through holes of diameter 10";
  part.nominal_wall = 4.0;
  SurfaceMesh mesh = make_box_solid(Vec3(0, 0, 0), Vec3(120, 80, 4));
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(20, 20), Eigen::Vector2d(100, 20),
                                  Eigen::Vector2d(20, 60), Eigen::Vector2d(100, 60)})
    mesh = mesh_difference(mesh, make_faceted_cylinder(c, 5.0, -1.0, 5.0, segments));
  part.mesh = std::move(mesh);
  part.label = [](const Vec3&, const Vec3& n) {
    return std::abs(n.z()) > 0.99 ? nominal(4.0) : rim(4.0);
  };
  return part;
}

LabelledPart l_bracket() {
  LabelledPart part;
  part.name = "l-bracket";
  part.description =
      "L-bracket, legs 60 and 40 long, 3 thick, 50 wide, with a 1.5 thick triangular gusset rib "
      "(legs 25) in the middle of its width";
  part.nominal_wall = 3.0;
  Polygon2 l(6, 2);
  l << 0, 0, 60, 0, 60, 3, 3, 3, 3, 40, 0, 40;
  Polygon2 gusset(3, 2);
  gusset << 2.9, 2.9, 28, 2.9, 2.9, 28;
  part.mesh = mesh_union(profile_extrusion(l, 0.0, 50.0), profile_extrusion(gusset, 24.25, 25.75));
  part.features.push_back(
      {"gusset rib", WallRole::thin_feature, 1.5, box(Vec3(3, 24.25, 3), Vec3(28, 25.75, 28))});
  const auto features = part.features;
  part.label = [features](const Vec3& x, const Vec3& n) {
    // The rib: its two faces, its sloping end (x + z = 30.9) and its top edge; the legs'
    // faces beside its ends (x + z beyond the slope) are the legs'.
    if (x.y() > 24.25 - kOn && x.y() < 25.75 + kOn && x.x() > 3 - kOn && x.z() > 3 - kOn &&
        x.x() + x.z() < 30.9 + kOn)
      return feature(features, 0);
    if (std::abs(n.y()) > 0.99 || near(x.x(), 60.0) || near(x.z(), 40.0)) return rim(3.0);
    return nominal(3.0);  // both legs, and the square corner where they meet
  };
  return part;
}

LabelledPart tube(int segments) {
  LabelledPart part;
  part.name = "tube";
  part.description = "tube, outer diameter 30, inner 24, 80 long (wall 3)";
  part.nominal_wall = 3.0;
  const int facets = 2 * segments;  // a CAD export facets a 30 mm tube finer than a 10 mm hole
  part.mesh = mesh_difference(
      make_faceted_cylinder(Eigen::Vector2d(15, 15), 15.0, 0.0, 80.0, facets),
      make_faceted_cylinder(Eigen::Vector2d(15, 15), 12.0, -1.0, 81.0, facets));
  part.label = [](const Vec3&, const Vec3& n) {
    return std::abs(n.z()) > 0.99 ? rim(3.0) : nominal(3.0);
  };
  return part;
}

LabelledPart boss_and_tab(int segments) {
  LabelledPart part;
  part.name = "boss-tab";
  part.description =
      "plate 100 x 60 x 4 with a solid boss of diameter 12 and height 10 on top, and a 2 thick "
      "tab 20 x 20 at one end";
  part.nominal_wall = 4.0;
  SurfaceMesh mesh = make_box_solid(Vec3(0, 0, 0), Vec3(100, 60, 4));
  mesh = mesh_union(mesh, make_box_solid(Vec3(99, 20, 0), Vec3(120, 40, 2)));
  mesh = mesh_union(mesh, make_faceted_cylinder(Eigen::Vector2d(30, 30), 6.0, 3.5, 14.0, segments));
  part.mesh = std::move(mesh);
  part.features.push_back(
      {"tab", WallRole::thin_feature, 2.0, box(Vec3(100, 20, 0), Vec3(120, 40, 2))});
  part.features.push_back(
      {"boss", WallRole::thick_feature, 12.0, box(Vec3(24, 24, 0), Vec3(36, 36, 14))});
  const auto features = part.features;
  part.label = [features](const Vec3& x, const Vec3& n) {
    if (x.x() > 100 + kOn) return feature(features, 0);
    const double r = std::hypot(x.x() - 30.0, x.y() - 30.0);
    if (r < 6.0 + kOn && x.z() > 4 - kOn) return feature(features, 1);
    if (r < 6.0 + kOn) return junction();  // the plate's bottom under the boss
    if (std::abs(n.z()) > 0.99) return nominal(4.0);
    return rim(4.0);
  };
  return part;
}

LabelledPart tray() {
  LabelledPart part;
  part.name = "tray";
  part.description =
      "open tray 100 x 80 x 30, walls and floor 2.5, the floor thinned to 1.2 over 20 x 20 by a "
      "pocket from below";
  part.nominal_wall = 2.5;
  SurfaceMesh mesh = make_box_solid(Vec3(0, 0, 0), Vec3(100, 80, 30));
  mesh = mesh_difference(mesh, make_box_solid(Vec3(2.5, 2.5, 2.5), Vec3(97.5, 77.5, 31)));
  mesh = mesh_difference(mesh, make_box_solid(Vec3(40, 30, -1), Vec3(60, 50, 1.3)));
  part.mesh = std::move(mesh);
  part.features.push_back(
      {"thinned pocket", WallRole::thin_feature, 1.2, box(Vec3(40, 30, 1.3), Vec3(60, 50, 2.5))});
  const auto features = part.features;
  part.label = [features](const Vec3& x, const Vec3& n) {
    const bool over_pocket = x.x() > 40 - kOn && x.x() < 60 + kOn && x.y() > 30 - kOn &&
                             x.y() < 50 + kOn;
    if (over_pocket && std::abs(n.z()) > 0.99 && x.z() > 1.3 - kOn && x.z() < 2.5 + kOn)
      return feature(features, 0);
    if (near(x.z(), 30.0) || (over_pocket && x.z() < 1.3 + kOn)) return rim(2.5);
    return nominal(2.5);
  };
  return part;
}

LabelledPart bent_bracket(int segments) {
  LabelledPart part;
  part.name = "bent-bracket";
  part.description =
      "sheet bracket 3 thick bent through 90 degrees about an inner radius of 4, legs 60 and 50, "
      "40 wide";
  part.nominal_wall = 3.0;
  const int arc = std::max(4, segments / 4);
  std::vector<Eigen::Vector2d> p = {{7, 0}, {60, 0}, {60, 3}};
  append_arc(p, {7, 7}, 4.0, -std::numbers::pi / 2, -std::numbers::pi, arc);  // (7,3) → (3,7)
  p.emplace_back(3, 50);
  p.emplace_back(0, 50);
  append_arc(p, {7, 7}, 7.0, std::numbers::pi, 1.5 * std::numbers::pi, arc);  // (0,7) → (7,0)
  p.pop_back();  // (7, 0) is the first corner
  part.mesh = profile_extrusion(to_polygon(p), 0.0, 40.0);
  part.label = [](const Vec3& x, const Vec3& n) {
    if (std::abs(n.y()) > 0.99 || near(x.x(), 60.0) || near(x.z(), 50.0)) return rim(3.0);
    return nominal(3.0);
  };
  return part;
}

LabelledPart filleted_junction(int segments) {
  LabelledPart part;
  part.name = "t-junction";
  part.description =
      "base plate 80 x 40 x 4 with a 4 thick wall 26 high standing on its middle, concave "
      "fillets of radius 2 where they meet";
  part.nominal_wall = 4.0;
  const int arc = std::max(2, segments / 8);
  std::vector<Eigen::Vector2d> p = {{0, 0}, {80, 0}, {80, 4}};
  append_arc(p, {44, 6}, 2.0, -std::numbers::pi / 2, -std::numbers::pi, arc);  // (44,4) → (42,6)
  p.emplace_back(42, 30);
  p.emplace_back(38, 30);
  append_arc(p, {36, 6}, 2.0, 0.0, -std::numbers::pi / 2, arc);  // (38,6) → (36,4)
  p.emplace_back(0, 4);
  part.mesh = profile_extrusion(to_polygon(p), 0.0, 40.0);
  part.label = [](const Vec3& x, const Vec3& n) {
    if (std::abs(n.y()) > 0.99 || near(x.x(), 0.0) || near(x.x(), 80.0) || near(x.z(), 30.0))
      return rim(4.0);
    if (x.x() > 36 - kOn && x.x() < 44 + kOn && x.z() < 6 + kOn) return junction();
    return nominal(4.0);
  };
  return part;
}

LabelledPart tapered_wall() {
  LabelledPart part;
  part.name = "taper";
  part.description = "wall 60 long and 40 wide whose thickness grows linearly from 2 to 6";
  part.nominal_wall = 4.0;
  Polygon2 p(4, 2);
  p << 0, 0, 60, 0, 60, 6, 0, 2;
  part.mesh = profile_extrusion(p, 0.0, 40.0);
  part.label = [](const Vec3& x, const Vec3& n) {
    const double t = 2.0 + 4.0 * std::clamp(x.x(), 0.0, 60.0) / 60.0;
    if (std::abs(n.z()) > 0.9) return nominal(t);
    return rim(t);
  };
  return part;
}

LabelledPart large_tray(int segments) {
  LabelledPart part;
  part.name = "large-tray";
  part.description =
      "open tray 356 x 356 x 60, walls and floor 3, a 3 x 3 grid of ribs 2 thick and 20 high on "
      "the floor (centred at 120 and 236 both ways), four solid bosses of diameter 10 and height "
      "20 in the corner cells";
  part.nominal_wall = 3.0;
  static constexpr double side = 356.0, height = 60.0, wall = 3.0, rib = 2.0, rib_top = 23.0;
  // Ribs and bosses start 0.1 inside the floor and walls they stand on, so that the unions
  // cut through faces instead of touching them.
  static constexpr double overlap = 0.1;
  static constexpr std::array<double, 2> rib_centres = {120.0, 236.0};
  static constexpr std::array<double, 2> boss_centres = {60.0, 296.0};
  static constexpr double boss_radius = 5.0;
  SurfaceMesh ribs;
  for (const double c : rib_centres) {
    const SurfaceMesh along_x = make_box_solid(Vec3(wall - overlap, c - rib / 2, wall - overlap),
                                               Vec3(side - wall + overlap, c + rib / 2, rib_top));
    const SurfaceMesh along_y = make_box_solid(Vec3(c - rib / 2, wall - overlap, wall - overlap),
                                               Vec3(c + rib / 2, side - wall + overlap, rib_top));
    ribs = ribs.num_faces() == 0 ? along_x : mesh_union(ribs, along_x);
    ribs = mesh_union(ribs, along_y);
  }
  SurfaceMesh mesh = make_box_solid(Vec3(0, 0, 0), Vec3(side, side, height));
  mesh = mesh_difference(mesh, make_box_solid(Vec3(wall, wall, wall),
                                              Vec3(side - wall, side - wall, height + 1.0)));
  mesh = mesh_union(mesh, ribs);
  for (const double bx : boss_centres)
    for (const double by : boss_centres) {
      mesh = mesh_union(mesh, make_faceted_cylinder(Eigen::Vector2d(bx, by), boss_radius,
                                                    wall - overlap, rib_top, segments));
      part.features.push_back({"boss at (" + std::to_string(static_cast<int>(bx)) + ", " +
                                   std::to_string(static_cast<int>(by)) + ")",
                               WallRole::thick_feature, 2 * boss_radius,
                               box(Vec3(bx - boss_radius, by - boss_radius, wall),
                                   Vec3(bx + boss_radius, by + boss_radius, rib_top))});
    }
  part.features.push_back({"ribs along x", WallRole::thin_feature, rib,
                           box(Vec3(wall, rib_centres[0] - rib / 2, wall),
                               Vec3(side - wall, rib_centres[1] + rib / 2, rib_top))});
  part.features.push_back({"ribs along y", WallRole::thin_feature, rib,
                           box(Vec3(rib_centres[0] - rib / 2, wall, wall),
                               Vec3(rib_centres[1] + rib / 2, side - wall, rib_top))});
  part.mesh = std::move(mesh);
  const auto features = part.features;
  part.label = [features](const Vec3& x, const Vec3& n) {
    const auto in_rib = [&](double coordinate) {
      for (const double c : rib_centres)
        if (std::abs(coordinate - c) < rib / 2 + kOn) return true;
      return false;
    };
    const bool in_cavity = x.x() > wall - kOn && x.x() < side - wall + kOn &&
                           x.y() > wall - kOn && x.y() < side - wall + kOn;
    const bool under_rib_height = x.z() < rib_top + kOn;
    int boss = -1;
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t j = 0; j < 2; ++j)
        if (std::hypot(x.x() - boss_centres[i], x.y() - boss_centres[j]) < boss_radius + kOn)
          boss = static_cast<int>(2 * i + j);
    const bool rib_x = in_rib(x.y()), rib_y = in_rib(x.x());
    if (in_cavity && under_rib_height && x.z() > wall - kOn) {
      if (boss >= 0) return feature(features, boss);
      if (rib_x && rib_y) return junction();  // where two ribs cross
      if (rib_x) return feature(features, 4);
      if (rib_y) return feature(features, 5);
    }
    // The floor's underside below a rib or a boss: the wall there is not 3 thick.
    if (n.z() < -0.99 && (boss >= 0 || (in_cavity && (rib_x || rib_y)))) return junction();
    if (near(x.z(), height)) return rim(wall);
    return nominal(wall);
  };
  return part;
}

}  // namespace

const char* to_string(WallRole role) {
  switch (role) {
    case WallRole::nominal: return "nominal";
    case WallRole::rim: return "rim";
    case WallRole::thin_feature: return "thin feature";
    case WallRole::thick_feature: return "thick feature";
    case WallRole::junction: return "junction";
  }
  return "?";
}

std::vector<WallLabel> LabelledPart::label_faces(const SurfaceMesh& surface) const {
  std::vector<WallLabel> labels(static_cast<std::size_t>(surface.num_faces()));
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f)
    labels[static_cast<std::size_t>(f)] = label(surface.face_centroids().row(f).transpose(),
                                                surface.face_normals().row(f).transpose());
  return labels;
}

std::vector<std::string> labelled_part_names() {
  return {"plate-holes", "l-bracket", "tube",       "boss-tab",
          "tray",        "bent-bracket", "t-junction", "taper",
          "large-tray"};
}

LabelledPart make_labelled_part(const std::string& name, int circle_segments) {
  if (circle_segments < 8) throw InputError("labelled parts need at least 8 facets per circle");
  if (name == "plate-holes") return plate_with_holes(circle_segments);
  if (name == "l-bracket") return l_bracket();
  if (name == "tube") return tube(circle_segments);
  if (name == "boss-tab") return boss_and_tab(circle_segments);
  if (name == "tray") return tray();
  if (name == "bent-bracket") return bent_bracket(circle_segments);
  if (name == "t-junction") return filleted_junction(circle_segments);
  if (name == "taper") return tapered_wall();
  if (name == "large-tray") return large_tray(circle_segments);
  std::string names;
  for (const std::string& n : labelled_part_names()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("unknown labelled part '" + name + "'; known: " + names);
}

}  // namespace bemshape::testing
