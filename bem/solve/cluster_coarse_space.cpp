#include "bem/solve/cluster_coarse_space.hpp"

#include <map>
#include <new>

#include "core/cancellation.hpp"
#include "core/memory_watch.hpp"

namespace bemshape::bem {

template <class Scalar>
ClusterCoarseSpace::ClusterCoarseSpace(const ClusterTree& tree, const HierarchicalMatrix& laplace,
                                       const YukawaNearField<Scalar>& yukawa,
                                       const Eigen::VectorXd& half_mass, Eigen::Index cluster_size,
                                       HierarchicalMatrix::GroupedColumns::Storage storage,
                                       const NestedFarField* far)
    : laplace_(laplace), far_(far), n_(tree.root().size()), half_mass_(half_mass) {
  std::vector<int> coarse = tree.clusters_up_to(cluster_size);
  while (Eigen::Index(coarse.size()) > kMaxClusters)
    coarse = tree.clusters_up_to(cluster_size *= 2);
  clusters_ = Eigen::Index(coarse.size());
  cluster_of_.resize(size_t(n_));
  for (Eigen::Index c = 0; c < clusters_; ++c) {
    const Cluster& cl = tree.cluster(coarse[size_t(c)]);
    for (Eigen::Index p = cl.begin; p < cl.end; ++p) cluster_of_[size_t(p)] = c;
  }
  const Eigen::Index m = clusters_;

  // Y (E ⊕ E): each row's entries summed per cluster of their column (a few clusters per
  // row: those within the exterior cutoff).
  {
    std::vector<std::vector<std::pair<std::int32_t, double>>> rows(static_cast<size_t>(n_));
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n_; ++i) {
      if (cancellation_requested()) continue;  // stopped, or out of memory (below)
      try {
        std::map<std::int32_t, double> sums;
        yukawa.for_each_in_row(i, [&](Eigen::Index j, double minus_k, double v) {
          const std::int32_t c = std::int32_t(cluster_of_[size_t(j)]);
          sums[c] += minus_k;
          sums[std::int32_t(m) + c] += v;
        });
        rows[size_t(i)].assign(sums.begin(), sums.end());
      } catch (const std::bad_alloc&) {
        note_failed_allocation();  // an exception cannot leave the loop: thrown below
      }
    }
    throw_if_cancelled();
    yukawa_grouped_.resize(n_, 2 * m);
    Eigen::VectorXi sizes(n_);
    for (Eigen::Index i = 0; i < n_; ++i) sizes(i) = int(rows[size_t(i)].size());
    yukawa_grouped_.reserve(sizes);
    for (Eigen::Index i = 0; i < n_; ++i)
      for (const auto& [c, v] : rows[size_t(i)]) yukawa_grouped_.insert(i, c) = v;
    yukawa_grouped_.makeCompressed();
  }

  // A_c = Pᵀ A P: the interior row from the H-matrix's sums, the exterior row from Y E,
  // then the mass terms ∓½ Eᵀ M E in the φ columns.
  // Only the LU is kept: A_c and the sums it is formed from, 8·(2m)² and 8·2m² bytes (134
  // and 67 MB at kMaxClusters), are dropped here.
  laplace_grouped_ = laplace.group_columns(cluster_of_, m, storage);
  Eigen::MatrixXd coarse_matrix = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  coarse_matrix.topRows(m) = laplace_grouped_.sums;
  laplace_grouped_.sums = Eigen::MatrixXd();
  if (far_)
    coarse_matrix.topRows(m) += far_->grouped_sums(cluster_of_, m);
  for (Eigen::Index i = 0; i < n_; ++i) {
    const Eigen::Index c = cluster_of_[size_t(i)];
    for (SparseRowMatrix::InnerIterator it(yukawa_grouped_, i); it; ++it)
      coarse_matrix(m + c, it.col()) += it.value();
    coarse_matrix(c, c) -= half_mass(i);
    coarse_matrix(m + c, c) += half_mass(i);
  }
  lu_.compute(coarse_matrix);
}

template ClusterCoarseSpace::ClusterCoarseSpace(const ClusterTree&, const HierarchicalMatrix&,
                                                const YukawaNearField<double>&,
                                                const Eigen::VectorXd&, Eigen::Index,
                                                HierarchicalMatrix::GroupedColumns::Storage,
                                                const NestedFarField*);
template ClusterCoarseSpace::ClusterCoarseSpace(const ClusterTree&, const HierarchicalMatrix&,
                                                const YukawaNearField<float>&,
                                                const Eigen::VectorXd&, Eigen::Index,
                                                HierarchicalMatrix::GroupedColumns::Storage,
                                                const NestedFarField*);

Eigen::MatrixXd ClusterCoarseSpace::coarse_solve(const Eigen::MatrixXd& r) const {
  const Eigen::Index m = clusters_;
  Eigen::MatrixXd restricted = Eigen::MatrixXd::Zero(2 * m, r.cols());
  for (Eigen::Index i = 0; i < n_; ++i) {
    const Eigen::Index c = cluster_of_[size_t(i)];
    restricted.row(c) += r.row(i);
    restricted.row(m + c) += r.row(n_ + i);
  }
  return lu_.solve(restricted);
}

void ClusterCoarseSpace::prolongate_add(const Eigen::MatrixXd& y, Eigen::MatrixXd& z) const {
  const Eigen::Index m = clusters_;
  for (Eigen::Index i = 0; i < n_; ++i) {
    const Eigen::Index c = cluster_of_[size_t(i)];
    z.row(i) += y.row(c);
    z.row(n_ + i) += y.row(m + c);
  }
}

Eigen::MatrixXd ClusterCoarseSpace::apply_operator(const Eigen::MatrixXd& y) const {
  const Eigen::Index m = clusters_, k = y.cols();
  Eigen::MatrixXd out(2 * n_, k);
  Eigen::MatrixXd densities(m, 2 * k);  // column 2j: φ of vector j, 2j + 1: its q
  for (Eigen::Index j = 0; j < k; ++j) {
    densities.col(2 * j) = y.col(j).head(m);
    densities.col(2 * j + 1) = y.col(j).tail(m);
  }
  Eigen::MatrixXd phi(n_, k);  // E y_φ
  for (Eigen::Index i = 0; i < n_; ++i) phi.row(i) = y.row(cluster_of_[size_t(i)]);
  out.topRows(n_).noalias() = -(half_mass_.asDiagonal() * phi);
  laplace_.multiply_add_grouped(laplace_grouped_, densities, out.topRows(n_));
  if (far_) {
    Eigen::MatrixXd expanded(n_, 2 * k);  // E applied to both densities
    for (Eigen::Index i = 0; i < n_; ++i)
      expanded.row(i) = densities.row(cluster_of_[size_t(i)]);
    far_->multiply_add(expanded, out.topRows(n_));
  }
  out.bottomRows(n_).noalias() = half_mass_.asDiagonal() * phi;
  out.bottomRows(n_) += yukawa_grouped_ * y;
  return out;
}

void ClusterCoarseSpace::apply_two_level(const ClusterBlockPreconditioner& blocks,
                                         const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const {
  const Eigen::MatrixXd y = coarse_solve(r);
  blocks.apply(r - apply_operator(y), z);
  prolongate_add(y, z);
}

std::uint64_t ClusterCoarseSpace::bytes() const {
  return 8ull * std::uint64_t(lu_.matrixLU().size()) + laplace_grouped_.bytes() +
         12ull * std::uint64_t(yukawa_grouped_.nonZeros()) + 8ull * cluster_of_.size();
}

}  // namespace bemshape::bem
