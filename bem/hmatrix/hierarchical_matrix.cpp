#include "bem/hmatrix/hierarchical_matrix.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <new>
#include <string>

#include <omp.h>

#include "linalg/mixed_precision_products.hpp"
#include "core/cancellation.hpp"

#include "core/assert.hpp"
#include "core/errors.hpp"

namespace bemshape::bem {
namespace {

/// Admissible blocks of at most this many entries are filled whole before the cross
/// approximation, which then reads its rows and columns from memory. Filling one row or one
/// column at a time costs a call per row or column (about 1–2 µs on the blocks of 16–64
/// panels), and ACA asks for some 50–75 of them on those blocks, where the ranks are 60–80 %
/// of the block's size; filling the whole block costs a third to a half of that. A block
/// whose approximation does not pay is then stored from the same entries instead of being
/// computed a second time. Measured per block class on the 28596-face hollow box
/// (docs/benchmarks.md, "H-matrix leaf size and ACA rank limit"): at 96–128 panels the whole block already costs as
/// much as ACA's rows and columns, hence 64 × 128 (64 panels against 64, two densities).
constexpr Eigen::Index kDenseFirstEntries = 64 * 128;

}  // namespace

Eigen::Index admissible_rank_limit(Eigen::Index rows, Eigen::Index cols, bool narrow) {
  // A rank at which U and V hold as many entries as the block gains nothing. With
  // fixed-point columns a factor entry takes about 2.3 bytes against a near-field entry's 4
  // (measured on spheres and boxes, docs/benchmarks.md), so ACA may go to 1.5 times that
  // rank; the stored bytes decide afterwards.
  const Eigen::Index equal_entries = std::max<Eigen::Index>(1, (rows * cols) / (rows + cols));
  return narrow ? std::min(std::min(rows, cols), (3 * equal_entries) / 2) : equal_entries;
}

std::optional<LowRankBlock> approximate_admissible_block(
    const OperatorBlockGenerator& generator, Eigen::Index row_begin, Eigen::Index row_end,
    Eigen::Index col_begin, Eigen::Index col_end, double epsilon, Eigen::Index max_rank,
    Eigen::MatrixXd& filled) {
  const int g = generator.densities(), o = generator.outputs();
  const Eigen::Index m = row_end - row_begin, n = col_end - col_begin;
  filled = Eigen::MatrixXd();
  // Small blocks are filled whole first (kDenseFirstEntries) and ACA reads them.
  if (o * m * g * n <= kDenseFirstEntries) {
    filled.resize(o * m, g * n);
    generator.fill(row_begin, row_end, col_begin, col_end, filled);
  }
  Eigen::MatrixXd column_block(o * m, g);
  Eigen::MatrixXd row_block(o, g * n);
  return adaptive_cross_approximation(
      o * m, g * n,
      [&](Eigen::Index i, Eigen::Ref<Eigen::VectorXd> row) {
        if (filled.size() > 0) {
          row = filled.row(i).transpose();
          return;
        }
        const Eigen::Index r = i % m;
        generator.fill(row_begin + r, row_begin + r + 1, col_begin, col_end, row_block);
        row = row_block.row(i / m).transpose();
      },
      [&](Eigen::Index j, Eigen::Ref<Eigen::VectorXd> column) {
        if (filled.size() > 0) {
          column = filled.col(j);
          return;
        }
        const Eigen::Index c = j % n, d = j / n;
        generator.fill(row_begin, row_end, col_begin + c, col_begin + c + 1, column_block);
        column = column_block.col(d);
      },
      epsilon, max_rank);
}

HierarchicalMatrix::HierarchicalMatrix(const ClusterTree& tree,
                                       const OperatorBlockGenerator& generator,
                                       const HierarchicalMatrixOptions& options,
                                       const ProgressCallback& progress)
    : HierarchicalMatrix(tree, tree, generator, options, progress) {}

HierarchicalMatrix::HierarchicalMatrix(const ClusterTree& row_tree, const ClusterTree& col_tree,
                                       const OperatorBlockGenerator& generator,
                                       const HierarchicalMatrixOptions& options,
                                       const ProgressCallback& progress)
    : HierarchicalMatrix(row_tree, col_tree, partition_blocks(row_tree, col_tree, options.eta),
                         generator, options, progress) {}

HierarchicalMatrix::HierarchicalMatrix(const ClusterTree& row_tree, const ClusterTree& col_tree,
                                       const BlockPartition& partition,
                                       const OperatorBlockGenerator& generator,
                                       const HierarchicalMatrixOptions& options,
                                       const ProgressCallback& progress)
    : rows_(row_tree.root().size()),
      cols_(col_tree.root().size()),
      densities_(generator.densities()),
      outputs_(generator.outputs()) {
  const int g = densities_, o = outputs_;
  blocks_.reserve(partition.admissible.size() + partition.dense.size());
  for (const auto* list : {&partition.dense, &partition.admissible})
    for (const BlockIndex& b : *list) {
      const Cluster& t = row_tree.cluster(b.rows);
      const Cluster& s = col_tree.cluster(b.cols);
      Block block;
      block.row_begin = t.begin;
      block.row_end = t.end;
      block.col_begin = s.begin;
      block.col_end = s.end;
      block.is_low_rank = list == &partition.admissible;
      blocks_.push_back(std::move(block));
    }
  // Large blocks first, so the dynamic schedule ends with small ones (load balance).
  std::stable_sort(blocks_.begin(), blocks_.end(), [](const Block& x, const Block& y) {
    return (x.row_end - x.row_begin) * (x.col_end - x.col_begin) >
           (y.row_end - y.row_begin) * (y.col_end - y.col_begin);
  });

  std::atomic<std::size_t> done{0};
  std::atomic<bool> out_of_memory{false};
  const std::size_t total = blocks_.size();
  std::vector<double> block_seconds(total, 0.0);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t k = 0; k < total; ++k) {
    // A cancelled run skips the remaining blocks (an exception cannot leave the loop).
    if (cancellation_requested() || out_of_memory) continue;
    const auto block_start = std::chrono::steady_clock::now();
    try {
      Block& b = blocks_[k];
      const Eigen::Index m = b.row_end - b.row_begin, n = b.col_end - b.col_begin;
      bool stored = false;
      const auto fill_whole = [&] {
        b.dense.resize(o * m, g * n);
        generator.fill(b.row_begin, b.row_end, b.col_begin, b.col_end, b.dense);
      };
      if (b.is_low_rank) {
        const bool narrow = options.single_precision_factors && options.fixed_point_columns &&
                            options.single_precision_near_field;
        auto aca = approximate_admissible_block(
            generator, b.row_begin, b.row_end, b.col_begin, b.col_end, options.aca_tolerance,
            admissible_rank_limit(o * m, g * n, narrow), b.dense);
        if (aca) {
          if (options.single_precision_factors) {
            b.factors = AdaptivePrecisionFactors(aca->U, aca->V, options.fixed_point_columns);
            b.single_precision = true;
            const std::uint64_t dense_bytes =
                (options.single_precision_near_field ? 4u : 8u) * std::uint64_t(o * m * g * n);
            stored = b.factors.bytes() < dense_bytes;
            if (!stored) b.factors = AdaptivePrecisionFactors();
          } else {
            b.low_rank = std::move(*aca);
            stored = true;
          }
        }
        if (stored) {
          b.dense = Eigen::MatrixXd();
        } else {
          b.is_low_rank = false;
          b.single_precision = false;
        }
      }
      if (!stored) {
        if (b.dense.size() == 0) fill_whole();  // not filled above
        if (options.single_precision_near_field) {
          b.dense_single = b.dense.cast<float>();
          b.dense = Eigen::MatrixXd();
          b.single_precision = true;
        }
      }
    } catch (const std::bad_alloc&) {
      out_of_memory = true;  // reported after the loop: an exception cannot leave it
    }
    block_seconds[k] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - block_start).count();
    const std::size_t finished = ++done;
    if (progress && finished % 256 == 0) {
#pragma omp critical(bemshape_progress)
      report_progress(progress, "assemble", double(finished) / double(total));
    }
  }
  throw_if_cancelled();
  if (out_of_memory)
    throw ResourceError("the hierarchical matrix of " + std::to_string(rows_) + " x " +
                        std::to_string(cols_) + " elements ran out of memory while assembling; "
                        "use a coarser mesh (larger --max-edge)");
  stats_.full_entries = std::uint64_t(o) * std::uint64_t(rows_) * std::uint64_t(g) * std::uint64_t(cols_);
  for (std::size_t k = 0; k < total; ++k) {
    const Block& b = blocks_[k];
    (b.is_low_rank ? stats_.low_rank_seconds : stats_.dense_seconds) += block_seconds[k];
    if (b.is_low_rank) {
      ++stats_.admissible_blocks;
      if (b.single_precision) {
        stats_.low_rank_entries += b.factors.entries();
        stats_.low_rank_bytes += b.factors.bytes();
        stats_.single_columns += std::uint64_t(b.factors.columns().single);
        stats_.fixed16_columns += std::uint64_t(b.factors.columns().fixed16);
        stats_.fixed8_columns += std::uint64_t(b.factors.columns().fixed8);
        stats_.max_rank = std::max(stats_.max_rank, b.factors.rank());
      } else {
        const auto entries = std::uint64_t(b.low_rank.U.size() + b.low_rank.V.size());
        stats_.low_rank_entries += entries;
        stats_.low_rank_bytes += 8 * entries;
        stats_.max_rank = std::max(stats_.max_rank, b.low_rank.rank());
      }
    } else {
      ++stats_.dense_blocks;
      const auto entries = std::uint64_t(b.single_precision ? b.dense_single.size() : b.dense.size());
      stats_.dense_entries += entries;
      stats_.dense_bytes += (b.single_precision ? 4 : 8) * entries;
    }
  }
}

namespace {

/// out += A x for A stored in single precision, in double arithmetic: the product reads 4
/// bytes per entry of A and writes no double copy of it.
void add_single_precision_product(const Eigen::MatrixXf& a, const Eigen::MatrixXd& x,
                                  Eigen::Ref<Eigen::MatrixXd> out) {
  linalg::add_scaled_columns(a.data(), a.rows(), a.rows(), a.cols(), nullptr, x, out);
}

/// out += U (Vᵀ x) for factors stored in single precision or narrower.
void add_narrow_factors_product(const AdaptivePrecisionFactors& factors, const Eigen::MatrixXd& x,
                                Eigen::Ref<Eigen::MatrixXd> out, Eigen::MatrixXd& t) {
  factors.multiply_v_transpose(x, t);
  factors.add_u_product(t, out);
}

}  // namespace

Eigen::MatrixXd gather_densities(const Eigen::Ref<const Eigen::MatrixXd>& x, int g,
                                 Eigen::Index begin, Eigen::Index n) {
  const Eigen::Index vectors = x.cols() / g;
  Eigen::MatrixXd xs(g * n, vectors);
  for (Eigen::Index j = 0; j < vectors; ++j)
    for (int d = 0; d < g; ++d) xs.col(j).segment(d * n, n) = x.col(j * g + d).segment(begin, n);
  return xs;
}

void HierarchicalMatrix::multiply_add(const Eigen::Ref<const Eigen::MatrixXd>& x,
                                      Eigen::Ref<Eigen::MatrixXd> y) const {
  const Eigen::Index vectors = x.cols() / densities_;
  BEMSHAPE_ASSERT(x.cols() == vectors * densities_ && y.cols() == vectors * outputs_ &&
                      x.rows() == cols_ && y.rows() == rows_,
                  "H-matrix product: x must be #cols × densities·k and y #rows × outputs·k");
  const int threads = omp_get_max_threads();
  std::vector<Eigen::MatrixXd> partial(static_cast<size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    Eigen::MatrixXd& mine = partial[static_cast<size_t>(omp_get_thread_num())];
    mine = Eigen::MatrixXd::Zero(rows_, y.cols());
    Eigen::MatrixXd product, t;
#pragma omp for schedule(static, 1)
    for (std::size_t k = 0; k < blocks_.size(); ++k) {
      const Block& b = blocks_[k];
      const Eigen::MatrixXd xs = gather_densities(x, densities_, b.col_begin, b.col_end - b.col_begin);
      const Eigen::Index m = b.row_end - b.row_begin;
      // The narrow blocks add straight into the rows of one output; the others, and several
      // outputs, go through `product`.
      const bool direct = outputs_ == 1 && b.single_precision;
      if (!direct) product.setZero(outputs_ * m, xs.cols());
      Eigen::Ref<Eigen::MatrixXd> target = direct ? Eigen::Ref<Eigen::MatrixXd>(mine.middleRows(b.row_begin, m))
                                                  : Eigen::Ref<Eigen::MatrixXd>(product);
      if (b.is_low_rank && b.single_precision)
        add_narrow_factors_product(b.factors, xs, target, t);
      else if (b.is_low_rank)
        product.noalias() = b.low_rank.U * (b.low_rank.V.transpose() * xs);
      else if (b.single_precision)
        add_single_precision_product(b.dense_single, xs, target);
      else
        product.noalias() = b.dense * xs;
      if (direct) continue;
      for (Eigen::Index j = 0; j < vectors; ++j)
        for (int o = 0; o < outputs_; ++o)
          mine.col(j * outputs_ + o).segment(b.row_begin, m) += product.col(j).segment(o * m, m);
    }
  }
  for (const Eigen::MatrixXd& p : partial) y += p;
}

std::vector<Eigen::MatrixXd> HierarchicalMatrix::diagonal_blocks(
    const std::vector<std::pair<Eigen::Index, Eigen::Index>>& ranges) const {
  BEMSHAPE_ASSERT(outputs_ == 1 && rows_ == cols_, "diagonal blocks of a square operator");
  // Which blocks meet which diagonal block: the ranges are sorted, so a binary search finds
  // the first range a block's rows reach.
  std::vector<std::vector<std::size_t>> meeting(ranges.size());
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const Block& b = blocks_[k];
    auto t = std::lower_bound(ranges.begin(), ranges.end(), b.row_begin,
                              [](const auto& range, Eigen::Index row) { return range.second <= row; });
    for (; t != ranges.end() && t->first < b.row_end; ++t)
      if (b.col_begin < t->second && t->first < b.col_end)
        meeting[static_cast<std::size_t>(t - ranges.begin())].push_back(k);
  }
  std::vector<Eigen::MatrixXd> out(ranges.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t t = 0; t < ranges.size(); ++t) {
    const auto [begin, end] = ranges[t];
    const Eigen::Index size = end - begin;
    out[t] = Eigen::MatrixXd::Zero(size, densities_ * size);
    for (const std::size_t k : meeting[t]) {
      const Block& b = blocks_[k];
      const Eigen::Index r0 = std::max(begin, b.row_begin), r1 = std::min(end, b.row_end);
      const Eigen::Index c0 = std::max(begin, b.col_begin), c1 = std::min(end, b.col_end);
      const Eigen::Index n = b.col_end - b.col_begin;
      for (int d = 0; d < densities_; ++d) {
        auto target = out[t].block(r0 - begin, d * size + (c0 - begin), r1 - r0, c1 - c0);
        const Eigen::Index u0 = r0 - b.row_begin, v0 = d * n + (c0 - b.col_begin);
        if (b.is_low_rank && b.single_precision)
          target.noalias() += b.factors.u_rows(u0, r1 - r0) * b.factors.v_rows(v0, c1 - c0).transpose();
        else if (b.is_low_rank)
          target.noalias() += b.low_rank.U.middleRows(u0, r1 - r0) *
                              b.low_rank.V.middleRows(v0, c1 - c0).transpose();
        else if (b.single_precision)
          target += b.dense_single.block(r0 - b.row_begin, d * n + (c0 - b.col_begin), r1 - r0, c1 - c0)
                        .cast<double>();
        else
          target += b.dense.block(r0 - b.row_begin, d * n + (c0 - b.col_begin), r1 - r0, c1 - c0);
      }
    }
  }
  return out;
}

std::uint64_t HierarchicalMatrix::GroupedColumns::bytes() const {
  std::uint64_t total = 8 * std::uint64_t(sums.size()) + 8 * group.size() + sizeof(Part) * parts.size();
  for (const Part& p : parts)
    total += 8 * std::uint64_t(p.values.size()) + p.fixed8.size() + 8 * p.scale.size();
  return total;
}

HierarchicalMatrix::GroupedColumns HierarchicalMatrix::group_columns(
    std::vector<Eigen::Index> group, Eigen::Index groups, GroupedColumns::Storage storage) const {
  BEMSHAPE_ASSERT(outputs_ == 1 && rows_ == cols_ && Eigen::Index(group.size()) == rows_,
                  "grouped columns of a square operator, one group per element");
  GroupedColumns out;
  out.group = std::move(group);
  out.groups = groups;
  out.parts.resize(blocks_.size());
  const std::vector<Eigen::Index>& of = out.group;
  const int g = densities_;
  const int threads = omp_get_max_threads();
  std::vector<Eigen::MatrixXd> partial(static_cast<size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    Eigen::MatrixXd& mine = partial[static_cast<size_t>(omp_get_thread_num())];
    mine = Eigen::MatrixXd::Zero(groups, g * groups);
    Eigen::MatrixXd left;
    // A static schedule: each thread sums the same blocks into `mine` on every run, so the
    // grouped sums (the coarse matrix) are the same to the last bit for a given thread count.
    // A dynamic one made them, and with them the solution, differ between runs in the
    // ninth digit.
#pragma omp for schedule(static, 16)
    for (std::size_t k = 0; k < blocks_.size(); ++k) {
      const Block& b = blocks_[k];
      const Eigen::Index m = b.row_end - b.row_begin, n = b.col_end - b.col_begin;
      // Groups are nondecreasing, so the block meets the consecutive groups r0 … and c0 ….
      const Eigen::Index r0 = of[size_t(b.row_begin)], c0 = of[size_t(b.col_begin)];
      const Eigen::Index nr = of[size_t(b.row_end - 1)] - r0 + 1;
      const Eigen::Index nc = of[size_t(b.col_end - 1)] - c0 + 1;
      GroupedColumns::Part& part = out.parts[k];
      Eigen::MatrixXd& values = part.values;
      if (!b.is_low_rank) {
        const Eigen::MatrixXd entries = dense_entries(b);
        values = Eigen::MatrixXd::Zero(m, g * nc);  // D E
        part.expanded = true;
        for (int d = 0; d < g; ++d)
          for (Eigen::Index j = 0; j < n; ++j)
            values.col(d * nc + of[size_t(b.col_begin + j)] - c0) += entries.col(d * n + j);
        for (Eigen::Index i = 0; i < m; ++i)
          for (int d = 0; d < g; ++d)
            mine.row(of[size_t(b.row_begin + i)]).segment(d * groups + c0, nc) +=
                values.row(i).segment(d * nc, nc);
      } else {
        const Eigen::MatrixXd u = b.single_precision ? b.factors.u_rows(0, m) : b.low_rank.U;
        const Eigen::MatrixXd v = b.single_precision ? b.factors.v_rows(0, g * n) : b.low_rank.V;
        const Eigen::Index rank = u.cols();
        values = Eigen::MatrixXd::Zero(g * nc, rank);  // EᵀV
        for (int d = 0; d < g; ++d)
          for (Eigen::Index j = 0; j < n; ++j)
            values.row(d * nc + of[size_t(b.col_begin + j)] - c0) += v.row(d * n + j);
        left = Eigen::MatrixXd::Zero(nr, rank);  // EᵀU
        for (Eigen::Index i = 0; i < m; ++i) left.row(of[size_t(b.row_begin + i)] - r0) += u.row(i);
        for (int d = 0; d < g; ++d)
          mine.block(r0, d * groups + c0, nr, nc).noalias() +=
              left * values.middleRows(d * nc, nc).transpose();
        if (g * nc <= rank) {  // A_d E = U (EᵀV)ᵀ holds no more numbers than U
          values = (u * values.transpose()).eval();
          part.expanded = true;
        }
      }
      if (part.expanded && storage == GroupedColumns::Storage::fixed8) {
        part.fixed8.resize(std::size_t(values.size()));
        part.scale.resize(std::size_t(values.cols()));
        for (Eigen::Index c = 0; c < values.cols(); ++c)
          linalg::to_fixed_point(values.col(c), part.fixed8.data() + c * m, part.scale[std::size_t(c)]);
        values = Eigen::MatrixXd();
      }
    }
  }
  out.sums = Eigen::MatrixXd::Zero(groups, g * groups);
  for (const Eigen::MatrixXd& p : partial) out.sums += p;
  return out;
}

void HierarchicalMatrix::multiply_add_grouped(const GroupedColumns& grouped,
                                              const Eigen::Ref<const Eigen::MatrixXd>& x,
                                              Eigen::Ref<Eigen::MatrixXd> y) const {
  const Eigen::Index vectors = x.cols() / densities_;
  BEMSHAPE_ASSERT(grouped.parts.size() == blocks_.size() && x.rows() == grouped.groups &&
                      x.cols() == vectors * densities_ && y.rows() == rows_ && y.cols() == vectors,
                  "grouped H-matrix product: x must be groups × densities·k and y #rows × k");
  const int threads = omp_get_max_threads();
  std::vector<Eigen::MatrixXd> partial(static_cast<size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    Eigen::MatrixXd& mine = partial[static_cast<size_t>(omp_get_thread_num())];
    mine = Eigen::MatrixXd::Zero(rows_, y.cols());
    Eigen::MatrixXd xs;
#pragma omp for schedule(static, 1)
    for (std::size_t k = 0; k < blocks_.size(); ++k) {
      const Block& b = blocks_[k];
      const Eigen::Index m = b.row_end - b.row_begin;
      const Eigen::Index c0 = grouped.group[size_t(b.col_begin)];
      const Eigen::Index nc = grouped.group[size_t(b.col_end - 1)] - c0 + 1;
      xs.resize(densities_ * nc, vectors);
      for (Eigen::Index j = 0; j < vectors; ++j)
        for (int d = 0; d < densities_; ++d)
          xs.col(j).segment(d * nc, nc) = x.col(j * densities_ + d).segment(c0, nc);
      const GroupedColumns::Part& part = grouped.parts[k];
      auto rows = mine.middleRows(b.row_begin, m);
      if (part.expanded && !part.fixed8.empty()) {
        linalg::add_scaled_columns(part.fixed8.data(), m, m, densities_ * nc, part.scale.data(), xs, rows);
      } else if (part.expanded) {
        rows.noalias() += part.values * xs;
      } else {
        const Eigen::MatrixXd t = part.values.transpose() * xs;  // rank × k
        if (b.single_precision)
          b.factors.add_u_product(t, rows);
        else
          rows.noalias() += b.low_rank.U * t;
      }
    }
  }
  for (const Eigen::MatrixXd& p : partial) y += p;
}

}  // namespace bemshape::bem
