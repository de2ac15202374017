#include "bem/hmatrix/nested_far_field.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "linalg/gram_orthogonalisation.hpp"
#include "linalg/mixed_precision_products.hpp"
#include "core/assert.hpp"
#include "core/cancellation.hpp"
#include "core/errors.hpp"

namespace bemshape::bem {
namespace {

using Clock = std::chrono::steady_clock;

/// Clusters of at least this many panels build their first child's subtree as a separate
/// OpenMP task; below, the tasks of the blocks' approximations are enough to fill two cores.
constexpr Eigen::Index kTaskClusterSize = 1024;

/// The leading left singular vectors of m (r × c) whose dropped singular values' squares add
/// up to at most tolerance²: r × k, orthonormal, by decreasing singular value. A wide m (many
/// blocks' columns on few rows, the usual case) goes by the eigenvectors X of its Gram matrix
/// m mᵀ (a symmetric rank-c update, half a matrix product of m's size), where a Householder
/// QR of mᵀ ran at a fifth of the rate (measured: 5 GFlop/s). The eigenvalues are the squared
/// singular values only to about u·λ_max; those below resolved_eigenvalues' share of the
/// largest are resolved again as orthogonalise_columns does: the columns mᵀX of the small
/// ones alone are orthogonalised, their Gram matrix's rounding relative to their own size
/// (linalg/gram_orthogonalisation.hpp), so the singular values near the truncation
/// are as accurate as an SVD's.
Eigen::MatrixXd leading_left_singular_vectors(const Eigen::MatrixXd& m, double tolerance) {
  if (m.rows() == 0 || m.cols() == 0)
    return Eigen::MatrixXd(m.rows(), 0);
  const double tolerance2 = tolerance * tolerance;
  Eigen::MatrixXd u;
  Eigen::VectorXd s;
  if (m.cols() > m.rows()) {
    const Eigen::Index r = m.rows();
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(r, r);
    gram.selfadjointView<Eigen::Lower>().rankUpdate(m);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
    u = eigen.eigenvectors();  // by ascending eigenvalue
    const Eigen::VectorXd& lambda = eigen.eigenvalues();
    s = lambda.cwiseMax(0.0).cwiseSqrt();
    const double norm = std::sqrt(std::max(lambda(r - 1), 0.0));
    const double resolved =
        linalg::resolved_eigenvalues(norm > 0.0 ? std::min(1.0, tolerance / norm) : 1.0);
    Eigen::Index small = 0;
    while (small < r && lambda(small) < resolved * lambda(r - 1))
      ++small;
    if (small >= 1) {
      // Their squared norms from the columns themselves (the eigenvalues are off by about
      // u·λ_max there); below what the truncation may drop in total, nothing needs resolving.
      Eigen::MatrixXd c = m.transpose() * u.leftCols(small);
      if (small >= 2 && c.squaredNorm() > tolerance2) {
        Eigen::MatrixXd w = u.leftCols(small);
        linalg::orthogonalise_columns(c, w, tolerance2, resolved);
        u.leftCols(small) = w;
      }
      s.head(small) = c.colwise().norm().transpose();
    }
    std::vector<Eigen::Index> order(static_cast<std::size_t>(r));
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = Eigen::Index(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](Eigen::Index x, Eigen::Index y) { return s(x) > s(y); });
    Eigen::MatrixXd sorted_u(r, r);
    Eigen::VectorXd sorted_s(r);
    for (Eigen::Index i = 0; i < r; ++i) {
      sorted_u.col(i) = u.col(order[std::size_t(i)]);
      sorted_s(i) = s(order[std::size_t(i)]);
    }
    u = std::move(sorted_u);
    s = std::move(sorted_s);
  } else {
    const Eigen::BDCSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeThinU);
    u = svd.matrixU();
    s = svd.singularValues();
  }
  Eigen::Index k = s.size();
  double dropped = 0.0;
  while (k > 0 && dropped + s(k - 1) * s(k - 1) <= tolerance2) {
    dropped += s(k - 1) * s(k - 1);
    --k;
  }
  return u.leftCols(k);
}

/// Depth of the tree below cluster t (a leaf: 1).
int depth(const ClusterTree& tree, int t) {
  const Cluster& c = tree.cluster(t);
  return c.is_leaf() ? 1 : 1 + std::max(depth(tree, c.first_child), depth(tree, c.first_child + 1));
}

/// One block's factor on the side being built, held while the subtree of its cluster on that
/// side (its "home") is built.
struct Contribution {
  std::size_t block = 0;
  std::shared_ptr<const Eigen::MatrixXd> factor;  ///< F_b, g·|home| × k_b (row d·|home| + i)
  /// Column scales w with ‖F_b diag(w)‖ the block's Gram weight at unit norm: row side
  /// (F = U, V orthonormal) 1/‖A_b‖_F; column side (F = V, U's columns of norms σ_i) σ_i/‖A_b‖_F.
  Eigen::VectorXd weight;
  Eigen::Index home_begin = 0, home_size = 0;
};

/// Q_tᵀ F_b|_t of one block for the cluster t it was computed at.
struct Projection {
  std::size_t block = 0;
  Eigen::MatrixXd value;  ///< k_t × k_b
};

/// The depth-first construction of one side (nested_far_field.hpp).
struct SideBuilder {
  const ClusterTree& tree;
  int g = 1;  ///< rows per panel on this side
  bool row_side = true;
  double cluster_tolerance = 0.0;                    ///< what each cluster may drop: tolerance/√L
  const std::vector<std::vector<std::size_t>>& own;  ///< per cluster: its blocks on this side
  /// The block's approximation, or nothing (not in the H² form).
  std::function<std::optional<LowRankBlock>(std::size_t)> approximate;
  /// Receives Q_homeᵀ F_b, the block's final projection on this side.
  std::function<void(std::size_t, Eigen::MatrixXd&&)> finish;
  std::vector<Eigen::Index>& rank;
  std::vector<Eigen::MatrixXf>& basis;
  std::atomic<bool>& out_of_memory;
  std::function<void(Eigen::Index)> leaf_done;  ///< progress: panels of a finished leaf
  std::atomic<double>* aca_seconds = nullptr;   ///< thread-seconds in the approximations
  std::atomic<double>* basis_seconds = nullptr;       ///< thread-seconds in the bases' SVDs
  std::atomic<std::uint64_t>* basis_flops = nullptr;  ///< Σ rows²·columns of the SVDs' inputs

  Eigen::MatrixXd restricted(const Contribution& a, const Cluster& c) const {
    Eigen::MatrixXd out(g * c.size(), a.factor->cols());
    for (int d = 0; d < g; ++d)
      out.middleRows(d * c.size(), c.size()) =
          a.factor->middleRows(d * a.home_size + (c.begin - a.home_begin), c.size());
    return out;
  }

  /// The blocks `active` (of t's ancestors) and t's own, restricted to t and weighted, as the
  /// columns whose left singular vectors make t's basis: `parts` (in t's rows, or in the
  /// children's bases) side by side.
  Eigen::MatrixXd weighted(const std::vector<Contribution>& active, const Cluster& c,
                           const std::vector<Eigen::MatrixXd>& parts) const {
    Eigen::Index columns = 0;
    for (const auto& p : parts)
      columns += p.cols();
    Eigen::MatrixXd m(parts.empty() ? 0 : parts.front().rows(), columns);
    Eigen::Index at = 0;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const double spread = std::sqrt(double(active[i].home_size) / double(c.size()));
      m.middleCols(at, parts[i].cols()) = parts[i] * (spread * active[i].weight).asDiagonal();
      at += parts[i].cols();
    }
    return m;
  }

  /// build_subtree, with a failed allocation turned into `out_of_memory` (an exception
  /// cannot leave an OpenMP task).
  std::vector<Projection> build(int t, std::vector<Contribution> active) const {
    try {
      return build_subtree(t, std::move(active));
    } catch (const std::bad_alloc&) {
      out_of_memory = true;
      return {};
    }
  }

  std::vector<Projection> build_subtree(int t, std::vector<Contribution> active) const {
    const Cluster& c = tree.cluster(t);
    if (out_of_memory || cancellation_requested())
      return {};
    const std::vector<std::size_t>& mine = own[std::size_t(t)];
    std::vector<std::optional<LowRankBlock>> computed(mine.size());
#pragma omp taskloop grainsize(1) shared(computed, mine)
    for (std::size_t i = 0; i < mine.size(); ++i) {
      if (out_of_memory || cancellation_requested())
        continue;
      try {
        const auto t0 = Clock::now();
        computed[i] = approximate(mine[i]);
        if (aca_seconds)
          *aca_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      } catch (const std::bad_alloc&) {
        out_of_memory = true;  // an exception cannot leave a task
      }
    }
    for (std::size_t i = 0; i < mine.size(); ++i) {
      if (!computed[i])
        continue;
      LowRankBlock& f = *computed[i];
      if (f.rank() == 1) {
        // recompress leaves rank-one factors as ACA made them (V's largest entry 1): give
        // them the form of the others, V orthonormal.
        const double v_norm = f.V.norm();
        if (v_norm > 0.0) {
          f.U *= v_norm;
          f.V /= v_norm;
        }
      }
      Contribution a;
      a.block = mine[i];
      const double norm = f.U.norm();  // ‖U Vᵀ‖_F: V is orthonormal
      const double scale = norm > 0.0 ? 1.0 / norm : 0.0;
      if (row_side) {
        a.weight = Eigen::VectorXd::Constant(f.rank(), scale);
        a.factor = std::make_shared<const Eigen::MatrixXd>(std::move(f.U));
      } else {
        a.weight = scale * f.U.colwise().norm().transpose();
        a.factor = std::make_shared<const Eigen::MatrixXd>(std::move(f.V));
      }
      a.home_begin = c.begin;
      a.home_size = c.size();
      active.push_back(std::move(a));
      computed[i].reset();
    }
    if (out_of_memory)
      return {};

    std::vector<Eigen::MatrixXd> parts(active.size());
    Eigen::MatrixXd q;
    if (c.is_leaf()) {
      for (std::size_t i = 0; i < active.size(); ++i)
        parts[i] = restricted(active[i], c);
      const auto t0 = Clock::now();
      const Eigen::MatrixXd m = weighted(active, c, parts);
      q = leading_left_singular_vectors(m, cluster_tolerance);
      if (basis_seconds)
        *basis_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      if (basis_flops)
        *basis_flops += std::uint64_t(m.rows() * m.rows() * m.cols());
      if (leaf_done)
        leaf_done(c.size());
    } else {
      std::vector<Projection> left, right;
#pragma omp task shared(left) if (c.size() >= kTaskClusterSize)
      left = build(c.first_child, active);
      right = build(c.first_child + 1, active);
#pragma omp taskwait
      if (out_of_memory || cancellation_requested())
        return {};
      // Beyond the entries of `active`, the children return their own blocks, now final.
      for (auto* child : {&left, &right})
        for (std::size_t i = active.size(); i < child->size(); ++i)
          finish((*child)[i].block, std::move((*child)[i].value));
      const Eigen::Index k1 = rank[std::size_t(c.first_child)],
                         k2 = rank[std::size_t(c.first_child + 1)];
      for (std::size_t i = 0; i < active.size(); ++i) {
        parts[i].resize(k1 + k2, left[i].value.cols());
        parts[i] << left[i].value, right[i].value;
      }
      Eigen::MatrixXd m = weighted(active, c, parts);
      if (active.empty())
        m.resize(k1 + k2, 0);
      const auto t0 = Clock::now();
      q = leading_left_singular_vectors(m, cluster_tolerance);
      if (basis_seconds)
        *basis_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      if (basis_flops)
        *basis_flops += std::uint64_t(m.rows() * m.rows() * m.cols());
    }
    std::vector<Projection> result(active.size());
    for (std::size_t i = 0; i < active.size(); ++i)
      result[i] = {active[i].block, q.transpose() * parts[i]};
    rank[std::size_t(t)] = q.cols();
    basis[std::size_t(t)] = q.cast<float>();
    return result;
  }
};

}  // namespace

NestedFarField::NestedFarField(const ClusterTree& tree, const std::vector<BlockIndex>& admissible,
                               const OperatorBlockGenerator& generator,
                               const NestedFarFieldOptions& options,
                               const ProgressCallback& progress)
    : tree_(&tree), densities_(generator.densities()) {
  BEMSHAPE_ASSERT(generator.outputs() == 1, "the H² far field is built for one output");
  const int g = densities_;
  const std::size_t clusters = tree.clusters().size(), count = admissible.size();
  const double basis_tolerance =
      options.basis_tolerance > 0.0 ? options.basis_tolerance : options.aca_tolerance;
  const double cluster_tolerance = basis_tolerance / std::sqrt(double(depth(tree, 0)));

  std::vector<std::vector<std::size_t>> own_rows(clusters), own_columns(clusters);
  for (std::size_t b = 0; b < count; ++b) {
    own_rows[std::size_t(admissible[b].rows)].push_back(b);
    own_columns[std::size_t(admissible[b].cols)].push_back(b);
  }
  // Blocks whose approximation reached the rank limit; written by one task per block.
  std::vector<char> dense(count, 0);
  const auto approximate = [&](std::size_t b) -> std::optional<LowRankBlock> {
    if (dense[b])
      return std::nullopt;
    const Cluster& t = tree.cluster(admissible[b].rows);
    const Cluster& s = tree.cluster(admissible[b].cols);
    Eigen::MatrixXd filled;
    auto aca = approximate_admissible_block(
        generator, t.begin, t.end, s.begin, s.end, options.aca_tolerance,
        admissible_rank_limit(t.size(), g * s.size(), true), filled);
    if (!aca)
      dense[b] = 1;
    return aca;
  };

  std::atomic<bool> out_of_memory{false};
  std::atomic<Eigen::Index> panels_done{0};
  const double total_panels = 2.0 * double(tree.root().size());
  const auto leaf_done = [&](Eigen::Index panels) {
    const Eigen::Index done = panels_done += panels;
    if (progress) {
#pragma omp critical(bemshape_progress)
      report_progress(progress, "assemble far field", double(done) / total_panels);
    }
  };
  std::atomic<double> aca_seconds{0.0}, basis_seconds{0.0};
  std::atomic<std::uint64_t> basis_flops{0};
  std::vector<Eigen::MatrixXf> row_projection(count);
  std::vector<Coupling> coupling(count);
  const auto run_side = [&](Side& side, int side_g, bool row_side,
                            const std::vector<std::vector<std::size_t>>& own,
                            const std::function<void(std::size_t, Eigen::MatrixXd &&)>& finish) {
    side.rank.assign(clusters, 0);
    side.basis.assign(clusters, Eigen::MatrixXf());
    const SideBuilder builder{
        tree,        side_g,       row_side,       cluster_tolerance, own,
        approximate, finish,       side.rank,      side.basis,        out_of_memory,
        leaf_done,   &aca_seconds, &basis_seconds, &basis_flops};
    std::vector<Projection> root;
#pragma omp parallel
#pragma omp single
    root = builder.build(0, {});
    for (Projection& p : root)
      finish(p.block, std::move(p.value));
  };

  auto start = Clock::now();
  run_side(rows_, 1, true, own_rows, [&](std::size_t b, Eigen::MatrixXd&& value) {
    row_projection[b] = value.cast<float>();
  });
  stats_.row_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  start = Clock::now();
  if (!out_of_memory)
    run_side(columns_, g, false, own_columns, [&](std::size_t b, Eigen::MatrixXd&& value) {
      // S_b = (Q_τᵀU_b)(P_σᵀV_b)ᵀ, or its two factors where they hold fewer numbers.
      Eigen::MatrixXf& left = row_projection[b];
      Coupling& out = coupling[b];
      BEMSHAPE_ASSERT(left.cols() == value.cols(),
                      "the two sides' cross approximations of a block differ in rank");
      if (left.rows() * value.rows() <= (left.rows() + value.rows()) * left.cols()) {
        out.left = (left.cast<double>() * value.transpose()).cast<float>();
      } else {
        out.left = std::move(left);
        out.right = value.cast<float>();
      }
      left = Eigen::MatrixXf();
    });
  stats_.column_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  stats_.aca_seconds = aca_seconds;
  stats_.basis_seconds = basis_seconds;
  stats_.basis_flops = basis_flops;
  throw_if_cancelled();
  if (out_of_memory)
    throw ResourceError("the H² far field of " + std::to_string(tree.root().size()) +
                        " elements ran out of memory while assembling; use a coarser mesh "
                        "(larger --max-edge)");

  blocks_of_row_.resize(clusters);
  for (std::size_t b = 0; b < count; ++b) {
    if (dense[b]) {
      uncompressed_.push_back(admissible[b]);
      continue;
    }
    blocks_of_row_[std::size_t(admissible[b].rows)].push_back(blocks_.size());
    blocks_.push_back(admissible[b]);
    couplings_.push_back(std::move(coupling[b]));
  }
  stats_.blocks = blocks_.size();
  stats_.uncompressed_blocks = uncompressed_.size();
  for (std::size_t c = 0; c < clusters; ++c) {
    const bool leaf = tree.cluster(int(c)).is_leaf();
    for (const Side* side : {&rows_, &columns_})
      (leaf ? stats_.leaf_basis_entries : stats_.transfer_entries) +=
          std::uint64_t(side->basis[c].size());
    stats_.max_row_rank = std::max(stats_.max_row_rank, rows_.rank[c]);
    stats_.max_column_rank = std::max(stats_.max_column_rank, columns_.rank[c]);
  }
  for (const Coupling& s : couplings_)
    stats_.coupling_entries += std::uint64_t(s.left.size() + s.right.size());
  stats_.bytes =
      4 * (stats_.leaf_basis_entries + stats_.transfer_entries + stats_.coupling_entries) +
      2 * clusters * (sizeof(Eigen::MatrixXf) + sizeof(Eigen::Index)) +
      blocks_.size() * (sizeof(Coupling) + sizeof(BlockIndex) + sizeof(std::size_t));
}

void NestedFarField::multiply_add(const Eigen::Ref<const Eigen::MatrixXd>& x,
                                  Eigen::Ref<Eigen::MatrixXd> y) const {
  const ClusterTree& tree = *tree_;
  const int g = densities_;
  const Eigen::Index vectors = x.cols() / g;
  const int clusters = int(tree.clusters().size());
  BEMSHAPE_ASSERT(x.cols() == g * vectors && y.cols() == vectors &&
                      x.rows() == tree.root().size() && y.rows() == tree.root().size(),
                  "H² product: x must be N × densities·k and y N × k");
  const auto columns_of = [](const Eigen::MatrixXf& a, const Eigen::Ref<const Eigen::MatrixXd>& c,
                             Eigen::Ref<Eigen::MatrixXd> out) {  // out += A c
    if (a.size() > 0)
      linalg::add_scaled_columns(a.data(), a.rows(), a.rows(), a.cols(), nullptr, c, out);
  };
  const auto dots_of = [](const Eigen::MatrixXf& a, const Eigen::Ref<const Eigen::MatrixXd>& c,
                          Eigen::Ref<Eigen::MatrixXd> out) {  // out += Aᵀ c
    if (a.size() > 0)
      linalg::add_scaled_column_dots(a.data(), a.rows(), a.rows(), a.cols(), nullptr, c, out);
  };
  std::vector<Eigen::MatrixXd> up(static_cast<std::size_t>(clusters)),
      down(static_cast<std::size_t>(clusters));
  const std::vector<int> leaves = tree.leaves();
  // Forward transformation: the leaves in parallel, then the inner clusters children first
  // (children have larger indices than their parent).
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const std::size_t t = std::size_t(leaves[i]);
    const Cluster& c = tree.cluster(leaves[i]);
    up[t] = Eigen::MatrixXd::Zero(columns_.rank[t], vectors);
    dots_of(columns_.basis[t], gather_densities(x, g, c.begin, c.size()), up[t]);
  }
  for (int t = clusters - 1; t >= 0; --t) {
    const Cluster& c = tree.cluster(t);
    if (c.is_leaf())
      continue;
    const auto& u1 = up[std::size_t(c.first_child)];
    const auto& u2 = up[std::size_t(c.first_child + 1)];
    Eigen::MatrixXd stacked(u1.rows() + u2.rows(), vectors);
    stacked << u1, u2;
    up[std::size_t(t)] = Eigen::MatrixXd::Zero(columns_.rank[std::size_t(t)], vectors);
    dots_of(columns_.basis[std::size_t(t)], stacked, up[std::size_t(t)]);
  }
  // Couplings, each row cluster's blocks summed by one thread.
#pragma omp parallel
  {
    Eigen::MatrixXd inner;
#pragma omp for schedule(dynamic, 16)
    for (int t = 0; t < clusters; ++t) {
      Eigen::MatrixXd& sum = down[std::size_t(t)];
      sum = Eigen::MatrixXd::Zero(rows_.rank[std::size_t(t)], vectors);
      for (const std::size_t b : blocks_of_row_[std::size_t(t)]) {
        const Coupling& s = couplings_[b];
        const Eigen::MatrixXd& source = up[std::size_t(blocks_[b].cols)];
        if (s.right.size() == 0) {
          columns_of(s.left, source, sum);
        } else {
          inner = Eigen::MatrixXd::Zero(s.right.cols(), vectors);
          dots_of(s.right, source, inner);
          columns_of(s.left, inner, sum);
        }
      }
    }
  }
  // Backward transformation: the inner clusters parents first, then the leaves.
  for (int t = 0; t < clusters; ++t) {
    const Cluster& c = tree.cluster(t);
    if (c.is_leaf())
      continue;
    auto& d1 = down[std::size_t(c.first_child)];
    auto& d2 = down[std::size_t(c.first_child + 1)];
    Eigen::MatrixXd stacked = Eigen::MatrixXd::Zero(d1.rows() + d2.rows(), vectors);
    columns_of(rows_.basis[std::size_t(t)], down[std::size_t(t)], stacked);
    d1 += stacked.topRows(d1.rows());
    d2 += stacked.bottomRows(d2.rows());
  }
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const Cluster& c = tree.cluster(leaves[i]);
    columns_of(rows_.basis[std::size_t(leaves[i])], down[std::size_t(leaves[i])],
               y.middleRows(c.begin, c.size()));
  }
}

Eigen::MatrixXd NestedFarField::grouped_sums(const std::vector<Eigen::Index>& group,
                                             Eigen::Index groups) const {
  const ClusterTree& tree = *tree_;
  const int g = densities_, clusters = int(tree.clusters().size());
  BEMSHAPE_ASSERT(Eigen::Index(group.size()) == tree.root().size(), "one group per element");
  const auto first = [&](const Cluster& c) { return group[std::size_t(c.begin)]; };
  const auto met = [&](const Cluster& c) { return group[std::size_t(c.end - 1)] - first(c) + 1; };
  // sums_of(side)[t]: basis_tᵀ E|_t, k_t × gs·met(t) (column d·met + a − first for density d).
  const auto sums_of = [&](const Side& side, int gs) {
    std::vector<Eigen::MatrixXd> out(static_cast<std::size_t>(clusters));
    for (int t = clusters - 1; t >= 0; --t) {  // children (larger indices) first
      const Cluster& c = tree.cluster(t);
      const Eigen::Index count = met(c), k = side.rank[std::size_t(t)];
      Eigen::MatrixXd grouped = Eigen::MatrixXd::Zero(c.is_leaf() ? gs * c.size() : 0, gs * count);
      if (c.is_leaf()) {
        for (int d = 0; d < gs; ++d)
          for (Eigen::Index i = 0; i < c.size(); ++i)
            grouped(d * c.size() + i, d * count + group[std::size_t(c.begin + i)] - first(c)) = 1.0;
      } else {
        Eigen::Index rows = 0;
        for (const int child : {c.first_child, c.first_child + 1})
          rows += out[std::size_t(child)].rows();
        grouped = Eigen::MatrixXd::Zero(rows, gs * count);
        Eigen::Index at = 0;
        for (const int child : {c.first_child, c.first_child + 1}) {
          const Cluster& ch = tree.cluster(child);
          const Eigen::MatrixXd& below = out[std::size_t(child)];
          const Eigen::Index child_count = met(ch), offset = first(ch) - first(c);
          for (int d = 0; d < gs; ++d)
            grouped.block(at, d * count + offset, below.rows(), child_count) =
                below.middleCols(d * child_count, child_count);
          at += below.rows();
        }
      }
      out[std::size_t(t)] =
          k > 0 ? Eigen::MatrixXd(side.basis[std::size_t(t)].cast<double>().transpose() * grouped)
                : Eigen::MatrixXd(0, gs * count);
    }
    return out;
  };
  const std::vector<Eigen::MatrixXd> row_sums = sums_of(rows_, 1),
                                     column_sums = sums_of(columns_, g);
  Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(groups, g * groups);
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const Cluster& t = tree.cluster(blocks_[b].rows);
    const Cluster& s = tree.cluster(blocks_[b].cols);
    const Eigen::MatrixXd left =
        row_sums[std::size_t(blocks_[b].rows)].transpose() * couplings_[b].matrix();
    const Eigen::Index nr = met(t), nc = met(s);
    const Eigen::MatrixXd& right = column_sums[std::size_t(blocks_[b].cols)];
    for (int d = 0; d < g; ++d)
      sums.block(first(t), d * groups + first(s), nr, nc).noalias() +=
          left * right.middleCols(d * nc, nc);
  }
  return sums;
}

Eigen::MatrixXd NestedFarField::Coupling::matrix() const {
  if (right.size() == 0)
    return left.cast<double>();
  return left.cast<double>() * right.cast<double>().transpose();
}

Eigen::MatrixXd NestedFarField::expand(const Side& side, int g, int c) const {
  const Cluster& cl = tree_->cluster(c);
  if (cl.is_leaf())
    return side.basis[std::size_t(c)].cast<double>();
  const Eigen::MatrixXd q1 = expand(side, g, cl.first_child),
                        q2 = expand(side, g, cl.first_child + 1);
  const Eigen::Index n1 = tree_->cluster(cl.first_child).size(),
                     n2 = tree_->cluster(cl.first_child + 1).size();
  const Eigen::MatrixXd transfer = side.basis[std::size_t(c)].cast<double>();
  Eigen::MatrixXd q(g * cl.size(), transfer.cols());
  for (int d = 0; d < g; ++d) {
    q.middleRows(d * cl.size(), n1) = q1.middleRows(d * n1, n1) * transfer.topRows(q1.cols());
    q.middleRows(d * cl.size() + n1, n2) =
        q2.middleRows(d * n2, n2) * transfer.bottomRows(q2.cols());
  }
  return q;
}

Eigen::MatrixXd NestedFarField::block(std::size_t b) const {
  return expand(rows_, 1, blocks_[b].rows) * couplings_[b].matrix() *
         expand(columns_, densities_, blocks_[b].cols).transpose();
}

}  // namespace bemshape::bem
