#include <catch2/catch.hpp>
#include <algorithm>

#include "geometry/constructive_solids.hpp"
#include "geometry/face_adjacency.hpp"

using namespace bemshape::geometry;

namespace {
bool lists(const std::vector<int>& neighbours, int g) {
  return std::find(neighbours.begin(), neighbours.end(), g) != neighbours.end();
}
}  // namespace

TEST_CASE("edge neighbours: three per face on a closed surface, symmetric, none shared by a corner only") {
  const SurfaceMesh box = make_box_solid({0, 0, 0}, {3, 2, 1});
  const auto neighbours = edge_neighbours(box.faces());
  REQUIRE(neighbours.size() == static_cast<std::size_t>(box.num_faces()));
  for (int f = 0; f < static_cast<int>(box.num_faces()); ++f) {
    CHECK(neighbours[static_cast<std::size_t>(f)].size() == 3);
    for (int g : neighbours[static_cast<std::size_t>(f)]) {
      CHECK(g != f);
      CHECK(lists(neighbours[static_cast<std::size_t>(g)], f));
      // They do share two corners.
      int shared = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          shared += box.faces()(f, i) == box.faces()(g, j);
      CHECK(shared == 2);
    }
  }
}

TEST_CASE("edge neighbours: a border has fewer, a non-manifold edge joins every face on it") {
  // Three triangles on the edge 0–1 (a non-manifold fan), and one more on edge 1–2 only.
  Eigen::MatrixX3i faces(4, 3);
  faces << 0, 1, 2,  //
      1, 0, 3,       //
      0, 1, 4,       //
      2, 1, 5;
  const auto neighbours = edge_neighbours(faces);
  CHECK(neighbours[0] == std::vector<int>{1, 2, 3});
  CHECK(neighbours[1] == std::vector<int>{0, 2});
  CHECK(neighbours[2] == std::vector<int>{0, 1});
  CHECK(neighbours[3] == std::vector<int>{0});
}
