// analysis/input_mesh.hpp: triangles from arrays are prepared as a file's are, and arrays that
// cannot bound a solid are refused with the reason.
#include <catch2/catch.hpp>
#include <cmath>

#include "analysis/input_mesh.hpp"
#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

TEST_CASE("prepare_triangles: a closed cube is kept, bad indices and holes are refused") {
  const geometry::SurfaceMesh cube =
      geometry::make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.5);
  const geometry::PreparedMesh prepared =
      analysis::prepare_triangles(cube.vertices(), cube.faces(), "cube");
  CHECK(prepared.report.source == "cube");
  CHECK(prepared.report.usable());
  CHECK(prepared.report.volume == Approx(1.0));
  CHECK(prepared.report.area == Approx(6.0));
  CHECK(prepared.mesh.num_faces() == cube.num_faces());

  Eigen::MatrixX3i out_of_range = cube.faces();
  out_of_range(3, 1) = static_cast<int>(cube.num_vertices());
  CHECK_THROWS_WITH(analysis::prepare_triangles(cube.vertices(), out_of_range, "cube"),
                    Catch::Contains("cube: face vertex indices must lie in [0, "));
  Eigen::MatrixX3d not_finite = cube.vertices();
  not_finite(0, 0) = std::nan("");
  CHECK_THROWS_AS(analysis::prepare_triangles(not_finite, cube.faces(), "cube"), InputError);
  const Eigen::MatrixX3i open = cube.faces().topRows(cube.num_faces() - 1);
  CHECK_THROWS_WITH(analysis::prepare_triangles(cube.vertices(), open, "cube"),
                    Catch::StartsWith("cube: ") && Catch::Contains("open boundary edges"));
}
