// bem/hmatrix/cluster_tree.hpp and block_partition.hpp: the tree is a balanced
// partition of the panels with boxes that hold them, and the block partition covers the
// matrix exactly once with admissible blocks that satisfy the condition.
#include <catch2/catch.hpp>

#include "bem/hmatrix/block_partition.hpp"
#include "bem/hmatrix/cluster_tree.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

TEST_CASE("cluster tree: a permutation, leaves tile the panels, boxes hold every corner") {
  const auto mesh = geometry::make_geodesic_sphere(1.0, 8);  // 1280 panels
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 20);
  std::vector<int> seen(panels.size(), 0);
  for (const Eigen::Index f : tree.permutation()) ++seen[size_t(f)];
  CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
  Eigen::Index next = 0;
  for (const int c : tree.leaves()) {
    const bem::Cluster& leaf = tree.cluster(c);
    CHECK(leaf.begin == next);
    CHECK(leaf.size() <= 20);
    CHECK(leaf.size() >= 10);  // median splits: balanced
    next = leaf.end;
  }
  CHECK(next == 1280);
  for (const bem::Cluster& c : tree.clusters())
    for (Eigen::Index p = c.begin; p < c.end; ++p)
      for (const auto& x : panels[size_t(tree.permutation()[size_t(p)])].corners) {
        CHECK((x.array() >= c.box.lo.array()).all());
        CHECK((x.array() <= c.box.hi.array()).all());
      }
  Eigen::Index covered = 0;
  for (const int c : tree.clusters_up_to(100)) covered += tree.cluster(c).size();
  CHECK(covered == 1280);
}

TEST_CASE("block partition: every entry in exactly one block, admissible blocks are far") {
  const auto mesh = geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 0.3), 0.1);
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 16);
  const double eta = 1.0;
  const bem::BlockPartition partition = bem::partition_blocks(tree, eta);
  const auto n = static_cast<Eigen::Index>(panels.size());
  Eigen::MatrixXi cover = Eigen::MatrixXi::Zero(n, n);
  for (const auto* list : {&partition.admissible, &partition.dense})
    for (const bem::BlockIndex& b : *list) {
      const bem::Cluster& t = tree.cluster(b.rows);
      const bem::Cluster& s = tree.cluster(b.cols);
      cover.block(t.begin, s.begin, t.size(), s.size()).array() += 1;
    }
  CHECK((cover.array() == 1).all());
  CHECK(!partition.admissible.empty());
  for (const bem::BlockIndex& b : partition.admissible) {
    const bem::Cluster& t = tree.cluster(b.rows);
    const bem::Cluster& s = tree.cluster(b.cols);
    CHECK(std::min(t.box.diameter(), s.box.diameter()) <= eta * t.box.distance(s.box));
  }
}
