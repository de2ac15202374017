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

void ClusterBlockPreconditioner::apply(const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const {
  z.resize(r.rows(), r.cols());
#pragma omp parallel for schedule(static)
  for (std::size_t t = 0; t < ranges_.size(); ++t) {
    const auto [begin, end] = ranges_[t];
    const Eigen::Index s = end - begin;
    Eigen::MatrixXd local(2 * s, r.cols());
    local.topRows(s) = r.middleRows(begin, s);
    local.bottomRows(s) = r.middleRows(n_ + begin, s);
    const Eigen::MatrixXd solved = factors_[t].solve(local);
    z.middleRows(begin, s) = solved.topRows(s);
    z.middleRows(n_ + begin, s) = solved.bottomRows(s);
  }
}

std::uint64_t ClusterBlockPreconditioner::bytes() const {
  std::uint64_t total = 0;
  for (const auto& f : factors_) total += 8 * std::uint64_t(f.matrixLU().size());
  return total;
}

}  // namespace bemshape::bem
