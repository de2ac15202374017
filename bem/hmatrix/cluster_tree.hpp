#pragma once
// Binary cluster tree over the panels of a mesh (or over target points): the index sets the
// hierarchical matrix (bem/hmatrix/hierarchical_matrix.hpp) and the near-field
// searches are organised by.
//
// Construction: the root holds every panel; a cluster with more than `leaf_size` panels is
// split at the median of its panels' centroids along the longest side of its bounding box,
// so the tree is balanced (depth ⌈log2(N/leaf_size)⌉) whatever the element sizes. Panels are
// renumbered so every cluster is a contiguous range [begin, end) of `permutation`:
// permutation[p] = the mesh face at tree position p.
//
// Bounding boxes enclose the panels' corners (not just their centroids), so the box distance
// between two clusters is a lower bound of the distance between any of their points — what
// the admissibility condition and the Yukawa cutoff need.

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "bem/quadrature/panel.hpp"

namespace bemshape::bem {

/// Axis-aligned box [lo, hi] [model units].
struct BoundingBox {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  void extend(const Eigen::Vector3d& x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  /// Length of the diagonal.
  double diameter() const { return (hi - lo).norm(); }
  /// Euclidean distance between the boxes (0 if they overlap).
  double distance(const BoundingBox& other) const {
    const Eigen::Vector3d gap =
        (other.lo - hi).cwiseMax(lo - other.hi).cwiseMax(Eigen::Vector3d::Zero());
    return gap.norm();
  }
};

struct Cluster {
  Eigen::Index begin = 0, end = 0;  ///< tree positions [begin, end)
  BoundingBox box;                  ///< encloses every corner of the cluster's panels
  int first_child = -1;             ///< index of the first of two children; −1 for a leaf
  Eigen::Index size() const { return end - begin; }
  bool is_leaf() const { return first_child < 0; }
};

class ClusterTree {
 public:
  /// Default leaf size: small enough that near-field blocks stay cheap, large enough that
  /// the per-block overhead of the H-matrix product does not dominate.
  static constexpr Eigen::Index kDefaultLeafSize = 32;

  /// Over panels: boxes around their corners, split by centroids.
  ClusterTree(const std::vector<Panel>& panels, Eigen::Index leaf_size = kDefaultLeafSize);
  /// Over points (#P×3): boxes around the points.
  ClusterTree(const Eigen::Ref<const Eigen::MatrixX3d>& points,
              Eigen::Index leaf_size = kDefaultLeafSize);

  const std::vector<Cluster>& clusters() const { return clusters_; }
  const Cluster& root() const { return clusters_.front(); }
  const Cluster& cluster(int index) const { return clusters_[static_cast<size_t>(index)]; }
  /// permutation()[p] = mesh face at tree position p.
  const std::vector<Eigen::Index>& permutation() const { return permutation_; }
  /// Indices of the leaves, in tree order (their ranges tile [0, N)).
  std::vector<int> leaves() const;
  /// Indices of the largest clusters with at most `max_size` panels, in tree order (their
  /// ranges tile [0, N)).
  std::vector<int> clusters_up_to(Eigen::Index max_size) const;
  /// Calls visit(leaf) for every leaf whose box lies within `reach` of `box`, depth first,
  /// left child first; clusters farther away are not descended into. `stack` is scratch
  /// space, reused across calls to spare allocations.
  template <class Visit>
  void for_each_leaf_near(const BoundingBox& box, double reach, std::vector<int>& stack,
                          Visit&& visit) const {
    stack.assign(1, 0);
    while (!stack.empty()) {
      const Cluster& cl = cluster(stack.back());
      stack.pop_back();
      if (box.distance(cl.box) > reach)
        continue;
      if (cl.is_leaf()) {
        visit(cl);
      } else {
        stack.push_back(cl.first_child + 1);
        stack.push_back(cl.first_child);
      }
    }
  }

 private:
  /// The construction for elements with the given centres (split coordinates) and the
  /// corners their boxes must hold (corners_per_element consecutive rows each).
  void build(const Eigen::MatrixX3d& centres, const Eigen::MatrixX3d& corners,
             int corners_per_element, Eigen::Index leaf_size);

  std::vector<Cluster> clusters_;
  std::vector<Eigen::Index> permutation_;
};

}  // namespace bemshape::bem
