#include <catch2/catch.hpp>

#include "geometry/primitive_meshes.hpp"
#include "geometry/winding_number.hpp"

using namespace bemshape::geometry;

TEST_CASE("winding number is 1 inside, 0 outside, -1 inside a reversed surface") {
  const SurfaceMesh box = make_box(Eigen::Vector3d(-1, -2, -3), Eigen::Vector3d(1, 2, 3), 0.7);
  const Eigen::Vector3d inside(0.9, -1.9, 2.5), outside(1.1, 0, 0), far(100, 50, -20);
  CHECK(winding_number(box.vertices(), box.faces(), inside) == Approx(1.0).margin(1e-12));
  CHECK(winding_number(box.vertices(), box.faces(), outside) == Approx(0.0).margin(1e-12));
  CHECK(winding_number(box.vertices(), box.faces(), far) == Approx(0.0).margin(1e-12));
  const SurfaceMesh flipped = with_flipped_orientation(box);
  CHECK(winding_number(flipped.vertices(), flipped.faces(), inside) == Approx(-1.0).margin(1e-12));
}
