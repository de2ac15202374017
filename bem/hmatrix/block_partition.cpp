#include "bem/hmatrix/block_partition.hpp"

#include <algorithm>

namespace bemshape::bem {

BlockPartition partition_blocks(const ClusterTree& tree, double eta) {
  return partition_blocks(tree, tree, eta);
}

BlockPartition partition_blocks(const ClusterTree& row_tree, const ClusterTree& col_tree,
                                double eta) {
  BlockPartition out;
  std::vector<BlockIndex> stack{{0, 0}};
  while (!stack.empty()) {
    const BlockIndex b = stack.back();
    stack.pop_back();
    const Cluster& t = row_tree.cluster(b.rows);
    const Cluster& s = col_tree.cluster(b.cols);
    const double distance = t.box.distance(s.box);
    if (std::min(t.box.diameter(), s.box.diameter()) <= eta * distance) {
      out.admissible.push_back(b);
    } else if (t.is_leaf() || s.is_leaf()) {
      // A leaf facing a large cluster: split the large one alone while that helps, so dense
      // blocks stay leaf-sized.
      if (t.is_leaf() && !s.is_leaf() && s.size() > 2 * t.size()) {
        stack.push_back({b.rows, s.first_child + 1});
        stack.push_back({b.rows, s.first_child});
      } else if (s.is_leaf() && !t.is_leaf() && t.size() > 2 * s.size()) {
        stack.push_back({t.first_child + 1, b.cols});
        stack.push_back({t.first_child, b.cols});
      } else {
        out.dense.push_back(b);
      }
    } else {
      for (int i = 1; i >= 0; --i)
        for (int j = 1; j >= 0; --j) stack.push_back({t.first_child + i, s.first_child + j});
    }
  }
  return out;
}

}  // namespace bemshape::bem
