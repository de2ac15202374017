#include "bem/hierarchical/cluster_tree.hpp"

#include <algorithm>
#include <numeric>

#include "core/errors.hpp"

namespace bemshape::bem {

ClusterTree::ClusterTree(const std::vector<Panel>& panels, Eigen::Index leaf_size) {
  if (leaf_size < 1) throw InternalError("ClusterTree: leaf size must be positive");
  const auto n = static_cast<Eigen::Index>(panels.size());
  permutation_.resize(panels.size());
  std::iota(permutation_.begin(), permutation_.end(), Eigen::Index{0});
  const auto box_of = [&](Eigen::Index begin, Eigen::Index end) {
    BoundingBox box;
    for (Eigen::Index p = begin; p < end; ++p)
      for (const auto& corner : panels[static_cast<size_t>(permutation_[size_t(p)])].corners)
        box.extend(corner);
    return box;
  };
  clusters_.push_back({0, n, box_of(0, n), -1});
  // Breadth-first: children are appended after their parents, siblings next to each other.
  for (size_t c = 0; c < clusters_.size(); ++c) {
    const Cluster parent = clusters_[c];
    if (parent.size() <= leaf_size) continue;
    Eigen::Index axis = 0;
    (parent.box.hi - parent.box.lo).maxCoeff(&axis);
    const Eigen::Index middle = parent.begin + parent.size() / 2;
    std::nth_element(permutation_.begin() + parent.begin, permutation_.begin() + middle,
                     permutation_.begin() + parent.end, [&](Eigen::Index x, Eigen::Index y) {
                       const double cx = panels[size_t(x)].centroid(axis);
                       const double cy = panels[size_t(y)].centroid(axis);
                       return cx < cy || (cx == cy && x < y);  // total order: deterministic
                     });
    clusters_[c].first_child = static_cast<int>(clusters_.size());
    clusters_.push_back({parent.begin, middle, box_of(parent.begin, middle), -1});
    clusters_.push_back({middle, parent.end, box_of(middle, parent.end), -1});
  }
}

std::vector<int> ClusterTree::leaves() const { return clusters_up_to(0); }

std::vector<int> ClusterTree::clusters_up_to(Eigen::Index max_size) const {
  std::vector<int> out, stack{0};
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    const Cluster& cl = cluster(c);
    if (cl.is_leaf() || cl.size() <= max_size) {
      out.push_back(c);
    } else {
      stack.push_back(cl.first_child + 1);  // depth first, left child first
      stack.push_back(cl.first_child);
    }
  }
  return out;
}

}  // namespace bemshape::bem
