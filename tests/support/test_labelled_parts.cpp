#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numbers>

#include "core/errors.hpp"
#include "tests/support/labelled_parts.hpp"
#include "geometry/mesh_preparation.hpp"

using namespace bemshape;
using namespace bemshape::geometry;
using namespace bemshape::testing;

namespace {
double polygon_area(double r, int segments) {
  return 0.5 * segments * r * r * std::sin(2.0 * std::numbers::pi / segments);
}

std::map<WallRole, double> area_by_role(const LabelledPart& part) {
  std::map<WallRole, double> area;
  const std::vector<WallLabel> labels = part.label_faces(part.mesh);
  for (Eigen::Index f = 0; f < part.mesh.num_faces(); ++f)
    area[labels[static_cast<std::size_t>(f)].role] += part.mesh.face_areas()(f);
  return area;
}
}  // namespace

TEST_CASE("labelled parts: every part is a clean solid of its design volume") {
  // Design volumes with the faceted circles of make_labelled_part's default 64 facets (128
  // for the tube).
  const std::map<std::string, double> volume = {
      {"plate-holes", 120 * 80 * 4 - 4 * polygon_area(5, 64) * 4},
      {"l-bracket", (60 * 3 + 3 * 37) * 50 + 0.5 * 24.9 * 24.9 * 1.5},  // gusset beyond the legs
      {"tube", (polygon_area(15, 128) - polygon_area(12, 128)) * 80},
      {"tray", 100 * 80 * 30 - 95 * 75 * 27.5 - 20 * 20 * 1.3},
      {"taper", 0.5 * (2 + 6) * 60 * 40},
      // Box minus cavity, four ribs 350 x 2 x 20 less their four 2 x 2 x 20 crossings counted
      // twice, four bosses.
      {"large-tray", 356.0 * 356 * 60 - 350.0 * 350 * 57 + 4 * 350 * 2 * 20 - 4 * 2 * 2 * 20 +
                         4 * polygon_area(5, 64) * 20},
  };
  for (const std::string& name : labelled_part_names()) {
    INFO(name);
    const LabelledPart part = make_labelled_part(name);
    TriangleSoup soup;
    soup.vertices = part.mesh.vertices();
    soup.faces = part.mesh.faces();
    const PreparedMesh prepared = inspect_triangle_soup(soup, name);
    INFO(prepared.report.refusal_message());
    REQUIRE(prepared.report.usable());
    CHECK(prepared.report.shells == 1);
    CHECK(prepared.report.cavities == 0);
    if (auto v = volume.find(name); v != volume.end())
      CHECK(part.mesh.signed_volume() == Approx(v->second).epsilon(1e-9));
  }
}

TEST_CASE("labelled parts: the labels cover the design's walls") {
  SECTION("plate with holes: the broad faces are nominal, the outline and the holes rims") {
    const LabelledPart part = make_labelled_part("plate-holes");
    auto area = area_by_role(part);
    CHECK(area[WallRole::nominal] == Approx(2 * (120 * 80 - 4 * polygon_area(5, 64))).epsilon(1e-9));
    const double hole_perimeter = 64 * 2 * 5 * std::sin(std::numbers::pi / 64);
    CHECK(area[WallRole::rim] == Approx(4 * (2 * (120 + 80) + 4 * hole_perimeter)).epsilon(1e-9));
  }
  SECTION("tube: the cylinders are nominal, the two annuli rims") {
    const LabelledPart part = make_labelled_part("tube");
    auto area = area_by_role(part);
    CHECK(area[WallRole::rim] == Approx(2 * (polygon_area(15, 128) - polygon_area(12, 128))).epsilon(1e-9));
    for (const WallLabel& label : part.label_faces(part.mesh)) CHECK(label.thickness == 3.0);
  }
  SECTION("tray: the thinned pocket's two faces are the thin feature, 1.2 thick") {
    const LabelledPart part = make_labelled_part("tray");
    REQUIRE(part.features.size() == 1);
    CHECK(part.features[0].thickness == 1.2);
    // The pocket's ceiling is faces of their own; the floor's top above it is not split along
    // the pocket's outline in the part's own (coarse) mesh, so it is checked point-wise.
    CHECK(area_by_role(part)[WallRole::thin_feature] == Approx(20 * 20).epsilon(1e-9));
    CHECK(part.label({50, 40, 2.5}, {0, 0, 1}).role == WallRole::thin_feature);
    CHECK(part.label({30, 40, 2.5}, {0, 0, 1}).role == WallRole::nominal);
  }
  SECTION("boss and tab: the tab is thin, the boss thick, both located in their boxes") {
    const LabelledPart part = make_labelled_part("boss-tab");
    REQUIRE(part.features.size() == 2);
    const auto labels = part.label_faces(part.mesh);
    for (Eigen::Index f = 0; f < part.mesh.num_faces(); ++f) {
      const WallLabel& label = labels[static_cast<std::size_t>(f)];
      if (label.feature < 0) continue;
      const BoundingBox& box = part.features[static_cast<std::size_t>(label.feature)].box;
      const Eigen::Vector3d c = part.mesh.face_centroids().row(f).transpose();
      CHECK((c.array() >= box.min.array() - 1e-9).all());
      CHECK((c.array() <= box.max.array() + 1e-9).all());
    }
  }
  SECTION("taper: the design thickness grows linearly from 2 to 6") {
    const LabelledPart part = make_labelled_part("taper");
    CHECK(part.label({0, 20, 0}, {0, 0, -1}).thickness == Approx(2.0));
    CHECK(part.label({30, 20, 0}, {0, 0, -1}).thickness == Approx(4.0));
    CHECK(part.label({60, 20, 6}, {0, 0, 1}).thickness == Approx(6.0));
  }
  SECTION("large tray: ribs thin, bosses thick, the floor below them a junction") {
    const LabelledPart part = make_labelled_part("large-tray");
    REQUIRE(part.features.size() == 6);
    CHECK(part.label({100, 119, 10}, {0, -1, 0}).role == WallRole::thin_feature);  // rib side
    CHECK(part.label({100, 119, 10}, {0, -1, 0}).thickness == 2.0);
    CHECK(part.label({236, 150, 23}, {0, 0, 1}).feature == 5);  // top of a rib along y
    CHECK(part.label({120, 236, 23}, {0, 0, 1}).role == WallRole::junction);  // a crossing
    CHECK(part.label({60, 60, 23}, {0, 0, 1}).role == WallRole::thick_feature);
    CHECK(part.label({296, 60, 0}, {0, 0, -1}).role == WallRole::junction);  // under a boss
    CHECK(part.label({150, 150, 3}, {0, 0, 1}).role == WallRole::nominal);    // floor
    CHECK(part.label({0, 150, 40}, {-1, 0, 0}).role == WallRole::nominal);    // side wall
    CHECK(part.label({150, 1.5, 60}, {0, 0, 1}).role == WallRole::rim);
    // The rib features' area: both sides (20 high) and top of four 350-long ribs, less the
    // crossings (the tops of four 2 x 2 squares and the sides cut out by the crossing ribs)
    // and the bosses' footprints do not touch them.
    double rib_area = 0.0;
    const auto labels = part.label_faces(part.mesh);
    for (Eigen::Index f = 0; f < part.mesh.num_faces(); ++f)
      if (labels[static_cast<std::size_t>(f)].role == WallRole::thin_feature)
        rib_area += part.mesh.face_areas()(f);
    CHECK(rib_area == Approx(4 * (2 * 350 * 20 + 350 * 2) - 4 * (2 * 2 * 2 * 20 + 2 * 2 * 2))
                          .epsilon(1e-9));
  }
  CHECK_THROWS_AS(make_labelled_part("no-such-part"), InputError);
}
