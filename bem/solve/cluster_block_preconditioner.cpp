#include "bem/solve/cluster_block_preconditioner.hpp"

#include <algorithm>
#include <cstddef>
#include <new>

#include "core/cancellation.hpp"
#include "core/memory_watch.hpp"

namespace bemshape::bem {

template <class Scalar>
ClusterBlockPreconditioner::ClusterBlockPreconditioner(const ClusterTree& tree,
                                                       const HierarchicalMatrix& laplace,
                                                       const YukawaNearField<Scalar>& yukawa,
                                                       const Eigen::VectorXd& half_mass,
                                                       Eigen::Index block_size)
    : n_(tree.root().size()) {
  for (const int c : tree.clusters_up_to(block_size))
    ranges_.emplace_back(tree.cluster(c).begin, tree.cluster(c).end);
  factors_.resize(ranges_.size());
  // The interior diagonal blocks in double precision, a chunk of clusters at a time: all of
  // them at once would hold 16·N·block_size bytes beside the operators (0.4 GB at 10⁵
  // faces).
  constexpr std::size_t kChunk = 64;
  for (std::size_t first = 0; first < ranges_.size(); first += kChunk) {
    const std::size_t last = std::min(ranges_.size(), first + kChunk);
    std::vector<Eigen::MatrixXd> interior = laplace.diagonal_blocks(
        {ranges_.begin() + std::ptrdiff_t(first), ranges_.begin() + std::ptrdiff_t(last)});
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t t = first; t < last; ++t) {
      if (cancellation_requested()) continue;  // stopped, or out of memory (below)
      try {
      // Plain variables, not a structured binding: the lambda below captures them, which
      // clang before 16 refuses for structured bindings.
      const Eigen::Index begin = ranges_[t].first, end = ranges_[t].second;
      const Eigen::Index s = end - begin;
      Eigen::MatrixXd local(2 * s, 2 * s);
      local.topRows(s) = interior[t - first];
      local.bottomRows(s).setZero();
      for (Eigen::Index r = 0; r < s; ++r) {
        local(r, r) -= half_mass(begin + r);
        local(s + r, r) += half_mass(begin + r);
        yukawa.for_each_in_row(begin + r, [&](Eigen::Index c, double minus_k, double v) {
          if (c >= begin && c < end) {
            local(s + r, c - begin) += minus_k;
            local(s + r, s + c - begin) += v;
          }
        });
      }
      interior[t - first].resize(0, 0);
      factors_[t] = linalg::FixedPointLu(local.cast<float>());
      } catch (const std::bad_alloc&) {
        note_failed_allocation();  // an exception cannot leave the loop: thrown below
      }
    }
    throw_if_cancelled();
  }
}

template ClusterBlockPreconditioner::ClusterBlockPreconditioner(const ClusterTree&,
                                                                const HierarchicalMatrix&,
                                                                const YukawaNearField<double>&,
                                                                const Eigen::VectorXd&, Eigen::Index);
template ClusterBlockPreconditioner::ClusterBlockPreconditioner(const ClusterTree&,
                                                                const HierarchicalMatrix&,
                                                                const YukawaNearField<float>&,
                                                                const Eigen::VectorXd&, Eigen::Index);

void ClusterBlockPreconditioner::apply(const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const {
  z.resize(r.rows(), r.cols());
#pragma omp parallel for schedule(static)
  for (std::size_t t = 0; t < ranges_.size(); ++t) {
    const auto [begin, end] = ranges_[t];
    const Eigen::Index s = end - begin;
    Eigen::MatrixXd local(2 * s, r.cols());
    local.topRows(s) = r.middleRows(begin, s);
    local.bottomRows(s) = r.middleRows(n_ + begin, s);
    factors_[t].solve_in_place(local);
    z.middleRows(begin, s) = local.topRows(s);
    z.middleRows(n_ + begin, s) = local.bottomRows(s);
  }
}

std::uint64_t ClusterBlockPreconditioner::bytes() const {
  std::uint64_t total = 0;
  for (const auto& f : factors_) total += f.bytes();
  return total;
}

}  // namespace bemshape::bem
