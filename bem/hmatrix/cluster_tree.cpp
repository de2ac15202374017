#include "bem/hmatrix/cluster_tree.hpp"

#include <algorithm>
#include <numeric>

#include "core/errors.hpp"

namespace bemshape::bem {

ClusterTree::ClusterTree(const std::vector<Panel>& panels, Eigen::Index leaf_size) {
  const auto n = static_cast<Eigen::Index>(panels.size());
  Eigen::MatrixX3d centres(n, 3), corners(3 * n, 3);
  for (Eigen::Index p = 0; p < n; ++p) {
    centres.row(p) = panels[size_t(p)].centroid.transpose();
    for (int k = 0; k < 3; ++k) corners.row(3 * p + k) = panels[size_t(p)].corners[size_t(k)].transpose();
  }
  build(centres, corners, 3, leaf_size);
}

ClusterTree::ClusterTree(const Eigen::Ref<const Eigen::MatrixX3d>& points, Eigen::Index leaf_size) {
  build(points, points, 1, leaf_size);
}

void ClusterTree::build(const Eigen::MatrixX3d& centres, const Eigen::MatrixX3d& corners,
                        int corners_per_element, Eigen::Index leaf_size) {
  if (leaf_size < 1) throw InternalError("ClusterTree: leaf size must be positive");
  const Eigen::Index n = centres.rows();
  permutation_.resize(size_t(n));
  std::iota(permutation_.begin(), permutation_.end(), Eigen::Index{0});
  const auto box_of = [&](Eigen::Index begin, Eigen::Index end) {
    BoundingBox box;
    for (Eigen::Index p = begin; p < end; ++p)
      for (int k = 0; k < corners_per_element; ++k)
        box.extend(corners.row(corners_per_element * permutation_[size_t(p)] + k).transpose());
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
                       const double cx = centres(x, axis), cy = centres(y, axis);
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
