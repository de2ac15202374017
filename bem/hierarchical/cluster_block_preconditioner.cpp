#include "bem/hierarchical/cluster_block_preconditioner.hpp"

namespace bemshape::bem {

ClusterBlockPreconditioner::ClusterBlockPreconditioner(const ClusterTree& tree,
                                                       const HierarchicalMatrix& laplace,
                                                       const SparseRowMatrix& yukawa,
                                                       const Eigen::VectorXd& half_mass,
                                                       Eigen::Index block_size)
    : n_(tree.root().size()) {
  for (const int c : tree.clusters_up_to(block_size))
    ranges_.emplace_back(tree.cluster(c).begin, tree.cluster(c).end);
  std::vector<Eigen::MatrixXd> interior = laplace.diagonal_blocks(ranges_);
  factors_.resize(ranges_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t t = 0; t < ranges_.size(); ++t) {
    const auto [begin, end] = ranges_[t];
    const Eigen::Index s = end - begin;
    Eigen::MatrixXd local(2 * s, 2 * s);
    local.topRows(s) = interior[t];
    local.bottomRows(s).setZero();
    for (Eigen::Index r = 0; r < s; ++r) {
      local(r, r) -= half_mass(begin + r);
      local(s + r, r) += half_mass(begin + r);
      for (SparseRowMatrix::InnerIterator it(yukawa, begin + r); it; ++it) {
        const Eigen::Index c = it.col();
        if (c >= begin && c < end)
          local(s + r, c - begin) += it.value();
        else if (c >= n_ + begin && c < n_ + end)
          local(s + r, s + c - n_ - begin) += it.value();
      }
    }
    interior[t].resize(0, 0);
    factors_[t].compute(local);
  }
}

void ClusterBlockPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
#pragma omp parallel for schedule(static)
  for (std::size_t t = 0; t < ranges_.size(); ++t) {
    const auto [begin, end] = ranges_[t];
    const Eigen::Index s = end - begin;
    Eigen::VectorXd local(2 * s);
    local.head(s) = r.segment(begin, s);
    local.tail(s) = r.segment(n_ + begin, s);
    const Eigen::VectorXd solved = factors_[t].solve(local);
    z.segment(begin, s) = solved.head(s);
    z.segment(n_ + begin, s) = solved.tail(s);
  }
}

std::uint64_t ClusterBlockPreconditioner::bytes() const {
  std::uint64_t total = 0;
  for (const auto& f : factors_) total += 8 * std::uint64_t(f.matrixLU().size());
  return total;
}

}  // namespace bemshape::bem
