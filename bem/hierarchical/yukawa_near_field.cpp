#include "bem/hierarchical/yukawa_near_field.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <new>
#include <string>
#include <cmath>
#include <vector>

#include "bem/galerkin_operators.hpp"
#include "bem/yukawa_kernel.hpp"
#include "core/assert.hpp"
#include "core/errors.hpp"
#include "core/cancellation.hpp"
#include "core/memory.hpp"

namespace bemshape::bem {

double yukawa_cutoff_gap(double kappa, double negligible) { return -std::log(negligible) / kappa; }

namespace {

/// Tree positions of the panels whose boxes come within `reach` of the test panel's box, in
/// increasing order (the candidates of one row).
void candidate_panels(const Panel& test, const ClusterTree& tree, double reach,
                      std::vector<Eigen::Index>& near, std::vector<int>& stack) {
  BoundingBox box;
  for (const auto& c : test.corners) box.extend(c);
  near.clear();
  tree.for_each_leaf_near(box, reach, stack, [&near](const Cluster& leaf) {
    for (Eigen::Index j = leaf.begin; j < leaf.end; ++j) near.push_back(j);
  });
  std::sort(near.begin(), near.end());
}

/// What decides which entries of a row are kept: the cutoff gap g* and the reach of the
/// candidate search around a panel's box.
struct Cutoff {
  double gap = 0.0, reach = 0.0;
  Cutoff(const std::vector<Panel>& panels, double kappa, double negligible) {
    double max_radius = 0.0;
    for (const Panel& p : panels) max_radius = std::max(max_radius, p.radius);
    // The dense path drops an entry when gap = |c_j − c_k| − r_j − r_k > g*; the distance
    // of the boxes around the panels is at most |c_j − c_k|, so clusters farther than
    // g* + 2·max radius hold no kept entry.
    gap = yukawa_cutoff_gap(kappa, negligible);
    reach = gap + 2.0 * max_radius;
  }
  bool kept(const Panel& test, const Panel& trial) const {
    return (test.centroid - trial.centroid).norm() - test.radius - trial.radius <= gap;
  }
};

ResourceError ran_out_of_memory(Eigen::Index n) {
  return ResourceError("the exterior near field of " + std::to_string(n) +
                       " faces ran out of memory while assembling; use a coarser mesh "
                       "(larger --max-edge)");
}

}  // namespace

Eigen::VectorX<Eigen::Index> yukawa_near_field_row_sizes(const std::vector<Panel>& panels,
                                                         const ClusterTree& tree, double kappa,
                                                         double negligible) {
  const auto& perm = tree.permutation();
  const Eigen::Index n = tree.root().size();
  const Cutoff cutoff(panels, kappa, negligible);
  Eigen::VectorX<Eigen::Index> room(n);
  std::atomic<bool> out_of_memory{false};
#pragma omp parallel
  {
    std::vector<Eigen::Index> near;
    std::vector<int> stack;
#pragma omp for schedule(dynamic, 64)
    for (Eigen::Index i = 0; i < n; ++i) {
      if (cancellation_requested() || out_of_memory) continue;
      try {
        const Panel& test = panels[size_t(perm[size_t(i)])];
        candidate_panels(test, tree, cutoff.reach, near, stack);
        Eigen::Index count = 0;
        for (const Eigen::Index j : near) count += cutoff.kept(test, panels[size_t(perm[size_t(j)])]);
        room(i) = 2 * count;
      } catch (const std::bad_alloc&) {
        out_of_memory = true;  // reported after the loop: an exception cannot leave it
      }
    }
  }
  throw_if_cancelled();
  if (out_of_memory) throw ran_out_of_memory(n);
  return room;
}

template <class Scalar>
SparseRowMatrixOf<Scalar> assemble_yukawa_near_field(const std::vector<Panel>& panels,
                                                     const ClusterTree& tree, double kappa,
                                                     double negligible,
                                                     const ProgressCallback& progress,
                                                     const Eigen::VectorX<Eigen::Index>* row_sizes) {
  const auto& perm = tree.permutation();
  const Eigen::Index n = tree.root().size();
  const Cutoff cutoff(panels, kappa, negligible);
  // Two passes, so that the rows are written straight into the matrix and nothing else of
  // its size is ever held: first each row's room (yukawa_near_field_row_sizes), then the
  // entries.
  Eigen::VectorX<Eigen::Index> counted;
  if (!row_sizes) counted = yukawa_near_field_row_sizes(panels, tree, kappa, negligible);
  const Eigen::VectorX<Eigen::Index>& room = row_sizes ? *row_sizes : counted;
  BEMSHAPE_ASSERT(room.size() == n, "exterior near field: one row size per panel");
  std::atomic<bool> out_of_memory{false};
  if (room.sum() > std::numeric_limits<std::int32_t>::max())
    throw ResourceError("the exterior near field of " + std::to_string(n) + " faces needs up to " +
                        std::to_string(room.sum()) + " entries, more than its 32-bit index allows (" +
                        std::to_string(std::numeric_limits<std::int32_t>::max()) +
                        "); use a coarser mesh (larger --max-edge)");
  // The exact size against the memory left now (the interior H-matrix is already held).
  require_memory((sizeof(Scalar) + 4) * std::uint64_t(room.sum()) + 8 * std::uint64_t(n),
                 "the exterior near field of " + std::to_string(n) + " faces (" +
                     std::to_string(room.sum()) + " entries)",
                 "use a coarser mesh (larger --max-edge)");
  SparseRowMatrixOf<Scalar> y(n, 2 * n);
  try {
    y.reserve(room);  // uncompressed: row i owns room(i) slots from outerIndexPtr()[i]
  } catch (const std::bad_alloc&) {
    throw ran_out_of_memory(n);
  }
  GalerkinOperators<YukawaKernel> yukawa(YukawaKernel{kappa}, panels);
  yukawa.tabulate_touching_pairs();
  std::int32_t* const columns = y.innerIndexPtr();
  Scalar* const values = y.valuePtr();
  const std::int32_t* const row_start = y.outerIndexPtr();
  std::int32_t* const row_size = y.innerNonZeroPtr();

  std::atomic<Eigen::Index> rows_done{0};
#pragma omp parallel
  {
    std::vector<Eigen::Index> near;
    std::vector<int> stack;
    std::vector<std::pair<std::int32_t, double>> single;
    std::vector<Eigen::Index> kept, faces;
    std::vector<GalerkinOperators<YukawaKernel>::Entry> entries;
    // Each row writes only its own slots, so the rows can be filled concurrently.
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index i = 0; i < n; ++i) {
      // A cancelled run skips the remaining rows (an exception cannot leave the parallel loop).
      if (cancellation_requested() || out_of_memory) continue;
      try {
        const Panel& test = panels[size_t(perm[size_t(i)])];
        candidate_panels(test, tree, cutoff.reach, near, stack);
        single.clear();
        std::int32_t* const row_columns = columns + row_start[i];
        Scalar* const row_values = values + row_start[i];
        std::int32_t count = 0;  // at most two per kept panel: within room(i)
        kept.clear();
        faces.clear();
        for (const Eigen::Index j : near) {
          if (!cutoff.kept(test, panels[size_t(perm[size_t(j)])])) continue;
          kept.push_back(j);
          faces.push_back(perm[size_t(j)]);
        }
        entries.resize(kept.size());
        yukawa.fill_row(perm[size_t(i)], faces, entries);
        for (size_t t = 0; t < kept.size(); ++t) {
          const Eigen::Index j = kept[t];
          const auto& e = entries[t];
          if (e.double_layer != 0.0) {
            row_columns[count] = static_cast<std::int32_t>(j);
            row_values[count++] = static_cast<Scalar>(-e.double_layer);
          }
          if (e.single_layer != 0.0)
            single.emplace_back(static_cast<std::int32_t>(n + j), e.single_layer);
        }
        for (const auto& [c, v] : single) {
          row_columns[count] = c;
          row_values[count++] = static_cast<Scalar>(v);
        }
        row_size[i] = count;
      } catch (const std::bad_alloc&) {
        out_of_memory = true;
      }
      const Eigen::Index done = ++rows_done;
      if (progress && done % 1024 == 0) {
#pragma omp critical(bemshape_progress)
        report_progress(progress, "assemble exterior", double(done) / double(n));
      }
    }
  }
  throw_if_cancelled();
  if (out_of_memory) throw ran_out_of_memory(n);
  // Left uncompressed: each row keeps its counted room, of which the coplanar zeros of Kκ
  // (flat walls) leave some unused. Compressing would close those gaps but reallocate the
  // storage to its exact size, holding both copies at once: the solver's peak memory (+0.8
  // GB at 50000 faces, measured). Products and iterators skip the unused slots.
  return y;
}

template SparseRowMatrixOf<double> assemble_yukawa_near_field<double>(
    const std::vector<Panel>&, const ClusterTree&, double, double, const ProgressCallback&,
    const Eigen::VectorX<Eigen::Index>*);
template SparseRowMatrixOf<float> assemble_yukawa_near_field<float>(
    const std::vector<Panel>&, const ClusterTree&, double, double, const ProgressCallback&,
    const Eigen::VectorX<Eigen::Index>*);

}  // namespace bemshape::bem
