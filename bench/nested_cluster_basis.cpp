#include "bench/nested_cluster_basis.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "bem/hmatrix/block_partition.hpp"
#include "bem/hmatrix/hierarchical_matrix.hpp"
#include "core/assert.hpp"

namespace bemshape::bench {

using bem::Cluster;
using bem::gather_densities;

namespace {

/// Upper-triangular R with FᵀF = RᵀR (Householder QR of F, n × k).
Eigen::MatrixXd triangular_factor(const Eigen::MatrixXd& f) {
  const Eigen::Index k = f.cols();
  if (f.rows() < k) {  // more columns than rows: R of F is k × k only when padded
    Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(k, k);
    padded.topRows(f.rows()) = f;
    return triangular_factor(padded);
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(f);
  return qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
}

/// Rows of F (g·parent × k, row d·parent + i) that belong to the sub-range [offset, offset +
/// size) of the parent's panels, for every density d: g·size × k.
Eigen::MatrixXd restrict_rows(const Eigen::MatrixXd& f, int g, Eigen::Index parent,
                              Eigen::Index offset, Eigen::Index size) {
  Eigen::MatrixXd out(g * size, f.cols());
  for (int d = 0; d < g; ++d)
    out.middleRows(d * size, size) = f.middleRows(d * parent + offset, size);
  return out;
}

/// One side of the construction: every block's factor on this side (F_b), its weight
/// (Rᵀ/‖A_b‖_F, R of the other factor) and its cluster on this side.
struct SideProblem {
  const ClusterTree& tree;
  int g = 1;
  double cluster_tolerance = 0.0;  ///< ε/√L: what each cluster may drop
  std::vector<const Eigen::MatrixXd*> factor;
  std::vector<Eigen::MatrixXd> weight;
  std::vector<int> cluster;
  std::vector<std::vector<std::size_t>> own;  ///< blocks whose cluster on this side is t
  NestedBasisSide* out = nullptr;
  std::vector<Eigen::MatrixXd>* transformed = nullptr;  ///< Q_tᵀ F_b for the block's own t

  /// The smallest leading part of the left singular vectors of m whose dropped singular
  /// values' squares add up to at most cluster_tolerance².
  Eigen::MatrixXd leading_singular_vectors(const Eigen::MatrixXd& m) const {
    if (m.cols() == 0 || m.rows() == 0)
      return Eigen::MatrixXd(m.rows(), 0);
    const Eigen::BDCSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeThinU);
    const Eigen::VectorXd& s = svd.singularValues();
    Eigen::Index k = s.size();
    double dropped = 0.0;
    while (k > 0 && dropped + s(k - 1) * s(k - 1) <= cluster_tolerance * cluster_tolerance) {
      dropped += s(k - 1) * s(k - 1);
      --k;
    }
    return svd.matrixU().leftCols(k);
  }

  /// The bases of t and below, for the blocks `active` of t's ancestors: returns Q_tᵀ F_b|_t
  /// for those blocks followed by t's own (k_t × k_b each), and stores the bases of t.
  std::vector<Eigen::MatrixXd> build(int t, std::vector<std::size_t> active) const {
    const Cluster& c = tree.cluster(t);
    active.insert(active.end(), own[std::size_t(t)].begin(), own[std::size_t(t)].end());
    std::vector<Eigen::MatrixXd> result(active.size());
    const auto weighted = [&](std::size_t b, const Eigen::MatrixXd& restricted) {
      const Cluster& home = tree.cluster(cluster[b]);
      return Eigen::MatrixXd(std::sqrt(double(home.size()) / double(c.size())) * restricted *
                             weight[b]);
    };
    Eigen::MatrixXd basis;
    if (c.is_leaf()) {
      std::vector<Eigen::MatrixXd> restricted(active.size());
      Eigen::Index columns = 0;
      for (std::size_t i = 0; i < active.size(); ++i) {
        const std::size_t b = active[i];
        const Cluster& home = tree.cluster(cluster[b]);
        restricted[i] = restrict_rows(*factor[b], g, home.size(), c.begin - home.begin, c.size());
        columns += restricted[i].cols();
      }
      Eigen::MatrixXd m(g * c.size(), columns);
      for (std::size_t i = 0, at = 0; i < active.size();
           at += std::size_t(restricted[i].cols()), ++i)
        m.middleCols(Eigen::Index(at), restricted[i].cols()) = weighted(active[i], restricted[i]);
      basis = leading_singular_vectors(m);
      for (std::size_t i = 0; i < active.size(); ++i)
        result[i] = basis.transpose() * restricted[i];
    } else {
      std::vector<Eigen::MatrixXd> left, right;
#pragma omp task shared(left) if (c.size() > 4096)
      left = build(c.first_child, active);
      right = build(c.first_child + 1, active);
#pragma omp taskwait
      const std::size_t mine = active.size();
      // The children's own blocks are done: their transformed factors are final.
      for (std::size_t i = mine; i < left.size(); ++i)
        (*transformed)[own[std::size_t(c.first_child)][i - mine]] = std::move(left[i]);
      for (std::size_t i = mine; i < right.size(); ++i)
        (*transformed)[own[std::size_t(c.first_child + 1)][i - mine]] = std::move(right[i]);
      const Eigen::Index k1 = out->rank[std::size_t(c.first_child)],
                         k2 = out->rank[std::size_t(c.first_child + 1)];
      std::vector<Eigen::MatrixXd> stacked(mine);
      Eigen::Index columns = 0;
      for (std::size_t i = 0; i < mine; ++i) {
        stacked[i].resize(k1 + k2, left[i].cols());
        stacked[i] << left[i], right[i];
        columns += stacked[i].cols();
      }
      Eigen::MatrixXd m(k1 + k2, columns);
      for (std::size_t i = 0, at = 0; i < mine; at += std::size_t(stacked[i].cols()), ++i)
        m.middleCols(Eigen::Index(at), stacked[i].cols()) = weighted(active[i], stacked[i]);
      basis = leading_singular_vectors(m);
      for (std::size_t i = 0; i < mine; ++i)
        result[i] = basis.transpose() * stacked[i];
    }
    out->rank[std::size_t(t)] = basis.cols();
    out->basis[std::size_t(t)] = std::move(basis);
    return result;
  }
};

/// Depth of the tree below cluster t (a leaf: 1).
int depth(const ClusterTree& tree, int t) {
  const Cluster& c = tree.cluster(t);
  return c.is_leaf() ? 1 : 1 + std::max(depth(tree, c.first_child), depth(tree, c.first_child + 1));
}

}  // namespace

Eigen::MatrixXd NestedBasisSide::expand(const ClusterTree& tree, int c) const {
  const Cluster& cl = tree.cluster(c);
  if (cl.is_leaf())
    return basis[std::size_t(c)];
  const Eigen::MatrixXd q1 = expand(tree, cl.first_child), q2 = expand(tree, cl.first_child + 1);
  const Eigen::Index n1 = tree.cluster(cl.first_child).size(),
                     n2 = tree.cluster(cl.first_child + 1).size();
  const Eigen::MatrixXd& transfer = basis[std::size_t(c)];
  const Eigen::Index k1 = q1.cols();
  Eigen::MatrixXd q(densities * cl.size(), transfer.cols());
  for (int d = 0; d < densities; ++d) {
    q.middleRows(d * cl.size(), n1) = q1.middleRows(d * n1, n1) * transfer.topRows(k1);
    q.middleRows(d * cl.size() + n1, n2) =
        q2.middleRows(d * n2, n2) * transfer.bottomRows(q2.cols());
  }
  return q;
}

NestedClusterBasis::NestedClusterBasis(
    const ClusterTree& tree, const std::vector<LowRankBlockCopy>& blocks,
    int densities, double tolerance) {
  // Clusters by their range, to find each block's clusters.
  std::map<std::pair<Eigen::Index, Eigen::Index>, int> by_range;
  for (int c = 0; c < int(tree.clusters().size()); ++c)
    by_range.emplace(std::pair{tree.cluster(c).begin, tree.cluster(c).end}, c);
  const auto cluster_of = [&](Eigen::Index begin, Eigen::Index end) {
    const auto it = by_range.find({begin, end});
    BEMSHAPE_ASSERT(it != by_range.end(),
                    "a block's rows or columns are not a cluster of the tree");
    return it->second;
  };
  leaf_.resize(tree.clusters().size());
  for (std::size_t c = 0; c < leaf_.size(); ++c)
    leaf_[c] = tree.clusters()[c].is_leaf();
  const std::size_t count = blocks.size();
  block_rank_.resize(count);
  row_cluster_.resize(count);
  column_cluster_.resize(count);
  blocks_of_row_.resize(tree.clusters().size());
  for (std::size_t b = 0; b < count; ++b) {
    block_rank_[b] = blocks[b].U.cols();
    row_cluster_[b] = cluster_of(blocks[b].row_begin, blocks[b].row_end);
    column_cluster_[b] = cluster_of(blocks[b].col_begin, blocks[b].col_end);
    blocks_of_row_[std::size_t(row_cluster_[b])].push_back(b);
  }
  const double cluster_tolerance = tolerance / std::sqrt(double(depth(tree, 0)));
  std::vector<Eigen::MatrixXd> u_weight(count), v_weight(count);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t b = 0; b < count; ++b) {
    const Eigen::MatrixXd ru = triangular_factor(blocks[b].U), rv = triangular_factor(blocks[b].V);
    const double norm = (ru * rv.transpose()).norm();  // ‖U Vᵀ‖_F
    const double scale = norm > 0.0 ? 1.0 / norm : 0.0;
    u_weight[b] = scale * rv.transpose();  // for the row side: F = U, weight Rᵀ of V
    v_weight[b] = scale * ru.transpose();
  }

  std::vector<Eigen::MatrixXd> row_transformed(count), column_transformed(count);
  const auto solve_side = [&](NestedBasisSide& side, int g, const std::vector<int>& clusters,
                              std::vector<Eigen::MatrixXd>& weights, bool u_side,
                              std::vector<Eigen::MatrixXd>& transformed) {
    side.densities = g;
    side.rank.assign(tree.clusters().size(), 0);
    side.basis.assign(tree.clusters().size(), Eigen::MatrixXd());
    SideProblem problem{tree, g,     cluster_tolerance, {}, std::move(weights), clusters,
                        {},   &side, &transformed};
    problem.factor.resize(count);
    problem.own.resize(tree.clusters().size());
    for (std::size_t b = 0; b < count; ++b) {
      problem.factor[b] = u_side ? &blocks[b].U : &blocks[b].V;
      problem.own[std::size_t(clusters[b])].push_back(b);
    }
    std::vector<Eigen::MatrixXd> root;
#pragma omp parallel
#pragma omp single
    root = problem.build(0, {});
    for (std::size_t i = 0; i < root.size(); ++i)
      transformed[problem.own[0][i]] = std::move(root[i]);
  };
  solve_side(rows_, 1, row_cluster_, u_weight, true, row_transformed);
  solve_side(columns_, densities, column_cluster_, v_weight, false, column_transformed);
  coupling_.resize(count);
  for (std::size_t b = 0; b < count; ++b)
    coupling_[b] = row_transformed[b] * column_transformed[b].transpose();
}

void NestedClusterBasis::multiply_add(const ClusterTree& tree,
                                      const Eigen::Ref<const Eigen::MatrixXd>& x,
                                      Eigen::Ref<Eigen::MatrixXd> y) const {
  const int g = columns_.densities;
  const Eigen::Index vectors = x.cols() / g;
  const int clusters = int(tree.clusters().size());
  BEMSHAPE_ASSERT(x.cols() == g * vectors && y.cols() == vectors &&
                      x.rows() == tree.root().size() && y.rows() == tree.root().size() &&
                      int(rows_.basis.size()) == clusters,
                  "H² product: x must be N × densities·k and y N × k, on the bases' tree");
  std::vector<Eigen::MatrixXd> up(static_cast<std::size_t>(clusters)),
      down(static_cast<std::size_t>(clusters));
  const std::vector<int> leaves = tree.leaves();
  // Forward transformation: the leaves (in parallel), then the inner clusters children first
  // (children have larger indices than their parent); the transfers are small.
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const Cluster& c = tree.cluster(leaves[i]);
    const Eigen::MatrixXd local = gather_densities(x, g, c.begin, c.size());
    up[std::size_t(leaves[i])] = columns_.basis[std::size_t(leaves[i])].transpose() * local;
  }
  for (int t = clusters - 1; t >= 0; --t) {
    const Cluster& c = tree.cluster(t);
    if (c.is_leaf())
      continue;
    const auto& u1 = up[std::size_t(c.first_child)];
    const auto& u2 = up[std::size_t(c.first_child + 1)];
    const Eigen::MatrixXd& transfer = columns_.basis[std::size_t(t)];
    up[std::size_t(t)] = transfer.topRows(u1.rows()).transpose() * u1 +
                         transfer.bottomRows(u2.rows()).transpose() * u2;
  }
  // Couplings, each row cluster's blocks summed by one thread.
#pragma omp parallel for schedule(dynamic, 16)
  for (int t = 0; t < clusters; ++t) {
    Eigen::MatrixXd& sum = down[std::size_t(t)];
    sum = Eigen::MatrixXd::Zero(rows_.rank[std::size_t(t)], vectors);
    for (const std::size_t b : blocks_of_row_[std::size_t(t)])
      sum.noalias() += coupling_[b] * up[std::size_t(column_cluster_[b])];
  }
  // Backward transformation: the inner clusters parents first, then the leaves.
  for (int t = 0; t < clusters; ++t) {
    const Cluster& c = tree.cluster(t);
    if (c.is_leaf())
      continue;
    const Eigen::MatrixXd& transfer = rows_.basis[std::size_t(t)];
    auto& d1 = down[std::size_t(c.first_child)];
    auto& d2 = down[std::size_t(c.first_child + 1)];
    d1.noalias() += transfer.topRows(d1.rows()) * down[std::size_t(t)];
    d2.noalias() += transfer.bottomRows(d2.rows()) * down[std::size_t(t)];
  }
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const Cluster& c = tree.cluster(leaves[i]);
    y.middleRows(c.begin, c.size()).noalias() +=
        rows_.basis[std::size_t(leaves[i])] * down[std::size_t(leaves[i])];
  }
}

NestedClusterBasis::Storage NestedClusterBasis::storage() const {
  Storage s;
  for (const NestedBasisSide* side : {&rows_, &columns_})
    for (std::size_t c = 0; c < side->basis.size(); ++c)
      (leaf_[c] ? s.leaf_basis_entries : s.transfer_entries) +=
          std::uint64_t(side->basis[c].size());
  for (std::size_t b = 0; b < coupling_.size(); ++b) {
    const Eigen::MatrixXd& m = coupling_[b];
    s.coupling_entries += std::uint64_t(m.size());
    s.factored_coupling_entries +=
        std::uint64_t(std::min(m.size(), (m.rows() + m.cols()) * block_rank_[b]));
  }
  return s;
}

double nested_basis_error_bound(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v,
                                const Eigen::MatrixXd& q, const Eigen::MatrixXd& p) {
  const Eigen::MatrixXd ru = triangular_factor(u), rv = triangular_factor(v);
  const double norm = (ru * rv.transpose()).norm();
  if (norm == 0.0)
    return 0.0;
  const double rows = ((u - q * (q.transpose() * u)) * rv.transpose()).norm();
  const double columns = (ru * (v - p * (p.transpose() * v)).transpose()).norm();
  return (rows + columns) / norm;
}

std::vector<LowRankBlockCopy> far_field_low_rank_blocks(
    const ClusterTree& tree, const bem::OperatorBlockGenerator& generator, double aca_tolerance,
    double eta) {
  std::vector<LowRankBlockCopy> blocks;
  for (const bem::BlockIndex& b : bem::partition_blocks(tree, eta).admissible) {
    const Cluster& t = tree.cluster(b.rows);
    const Cluster& s = tree.cluster(b.cols);
    blocks.push_back({t.begin, t.end, s.begin, s.end, {}, {}});
  }
  // The H-matrix's order: larger blocks first, ties in the partition's order.
  const auto entries = [](const LowRankBlockCopy& b) {
    return (b.row_end - b.row_begin) * (b.col_end - b.col_begin);
  };
  std::stable_sort(blocks.begin(), blocks.end(),
                   [&](const LowRankBlockCopy& x, const LowRankBlockCopy& y) {
                     return entries(x) > entries(y);
                   });
  const int g = generator.densities(), o = generator.outputs();
  std::vector<char> low_rank(blocks.size(), 0);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    LowRankBlockCopy& b = blocks[k];
    const Eigen::Index m = b.row_end - b.row_begin, n = b.col_end - b.col_begin;
    Eigen::MatrixXd filled;
    auto aca = bem::approximate_admissible_block(generator, b.row_begin, b.row_end, b.col_begin,
                                                 b.col_end, aca_tolerance,
                                                 bem::admissible_rank_limit(o * m, g * n, false),
                                                 filled);
    if (aca) {
      b.U = std::move(aca->U);
      b.V = std::move(aca->V);
      low_rank[k] = 1;
    }
  }
  std::vector<LowRankBlockCopy> out;
  for (std::size_t k = 0; k < blocks.size(); ++k)
    if (low_rank[k]) out.push_back(std::move(blocks[k]));
  return out;
}

}  // namespace bemshape::bench
