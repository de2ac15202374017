#include "bem/solve/yukawa_near_field.hpp"

#include <atomic>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <new>
#include <string>
#include <type_traits>
#include <cmath>
#include <vector>

#include "bem/operators/galerkin_operators.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "core/assert.hpp"
#include "core/errors.hpp"
#include "core/cancellation.hpp"
#include "core/memory.hpp"

namespace bemshape::bem {

double yukawa_cutoff_distance(double kappa, double negligible) { return -std::log(negligible) / kappa; }

namespace {

/// What decides which entries of a row are kept: the gap between the panels' bounding
/// balls, gap = |c_i − c_j| − r_i − r_j (a lower bound on the distance between the panels),
/// against the cutoff distance R*. Between centroids alone the test would drop touching
/// pairs of panels larger than R*: on a graded mesh, panels of 4·h0 against R* = 18.4/κ =
/// 1.8·h0, which moved a 4 mm plate's median wall by 0.26 % against the dense path's.
/// The candidate search around a panel's box reaches R* + r_i + r_max: the centroid of a
/// panel lies in its box, so two panels within the cutoff have boxes no farther apart than
/// that. The centroids and radii are copied in tree order, so that a leaf's candidates are
/// read contiguously.
struct Cutoff {
  double distance = 0.0;
  double largest_radius = 0.0;
  Eigen::Matrix3Xd centroids;  ///< column j: the centroid of the panel at tree position j
  Eigen::VectorXd radii;       ///< entry j: its radius about the centroid
  Cutoff(const std::vector<Panel>& panels, const ClusterTree& tree, double kappa, double negligible)
      : distance(yukawa_cutoff_distance(kappa, negligible)),
        centroids(3, Eigen::Index(panels.size())),
        radii(Eigen::Index(panels.size())) {
    const auto& perm = tree.permutation();
    for (Eigen::Index j = 0; j < centroids.cols(); ++j) {
      const Panel& panel = panels[size_t(perm[size_t(j)])];
      centroids.col(j) = panel.centroid;
      radii(j) = panel.radius;
      largest_radius = std::max(largest_radius, panel.radius);
    }
  }
  double reach(const Panel& test) const { return distance + test.radius + largest_radius; }
  bool kept(const Panel& test, Eigen::Index j) const {
    const double within = distance + test.radius + radii(j);
    return (test.centroid - centroids.col(j)).squaredNorm() <= within * within;
  }
};

/// The columns of one row: tree positions, in increasing order, of the panels the cutoff
/// keeps for `test` among those whose boxes come within its reach of its box (the leaves
/// are visited left to right, so the positions come out sorted). `stack` is scratch space.
void row_columns(const Panel& test, const ClusterTree& tree, const Cutoff& cutoff,
                 std::vector<int>& stack, std::vector<Eigen::Index>& columns) {
  BoundingBox box;
  for (const auto& c : test.corners) box.extend(c);
  columns.clear();
  tree.for_each_leaf_near(box, cutoff.reach(test), stack, [&](const Cluster& leaf) {
    for (Eigen::Index j = leaf.begin; j < leaf.end; ++j)
      if (cutoff.kept(test, j)) columns.push_back(j);
  });
}

ResourceError ran_out_of_memory(Eigen::Index n) {
  return ResourceError("the exterior near field of " + std::to_string(n) +
                       " faces ran out of memory while assembling; use a coarser mesh "
                       "(larger --max-edge)");
}

}  // namespace

Eigen::Index yukawa_near_field_runs(const std::vector<Eigen::Index>& columns) {
  Eigen::Index runs = 0;
  YukawaNearField<float>::for_each_run(columns, [&runs](Eigen::Index, Eigen::Index) { ++runs; });
  return runs;
}

YukawaNearFieldRows yukawa_near_field_rows(const std::vector<Panel>& panels, const ClusterTree& tree,
                                           double kappa, double negligible) {
  const auto& perm = tree.permutation();
  const Eigen::Index n = tree.root().size();
  const Cutoff cutoff(panels, tree, kappa, negligible);
  YukawaNearFieldRows rows{Eigen::VectorX<Eigen::Index>(n), Eigen::VectorX<Eigen::Index>(n)};
  std::atomic<bool> out_of_memory{false};
#pragma omp parallel
  {
    std::vector<Eigen::Index> kept;
    std::vector<int> stack;
#pragma omp for schedule(dynamic, 64)
    for (Eigen::Index i = 0; i < n; ++i) {
      if (cancellation_requested() || out_of_memory) continue;
      try {
        const Panel& test = panels[size_t(perm[size_t(i)])];
        row_columns(test, tree, cutoff, stack, kept);
        rows.pairs(i) = Eigen::Index(kept.size());
        rows.runs(i) = yukawa_near_field_runs(kept);
      } catch (const std::bad_alloc&) {
        out_of_memory = true;  // reported after the loop: an exception cannot leave it
      }
    }
  }
  throw_if_cancelled();
  if (out_of_memory) throw ran_out_of_memory(n);
  return rows;
}

template <class Scalar>
YukawaNearField<Scalar> assemble_yukawa_near_field(const std::vector<Panel>& panels,
                                                   const ClusterTree& tree, double kappa,
                                                   double negligible,
                                                   const ProgressCallback& progress,
                                                   const YukawaNearFieldRows* rows,
                                                   double accuracy) {
  const auto& perm = tree.permutation();
  const Eigen::Index n = tree.root().size();
  const Cutoff cutoff(panels, tree, kappa, negligible);
  // Two passes, so that the rows are written straight into the matrix and nothing else of
  // its size is ever held: first each row's pairs and runs (yukawa_near_field_rows), then the
  // entries.
  YukawaNearFieldRows counted;
  if (!rows) counted = yukawa_near_field_rows(panels, tree, kappa, negligible);
  const YukawaNearFieldRows& room = rows ? *rows : counted;
  BEMSHAPE_ASSERT(room.pairs.size() == n && room.runs.size() == n,
                  "exterior near field: one row size per panel");
  std::atomic<bool> out_of_memory{false};
  const Eigen::Index pairs = room.pairs.sum(), runs = room.runs.sum();
  if (pairs > std::numeric_limits<std::int32_t>::max())
    throw ResourceError("the exterior near field of " + std::to_string(n) + " faces needs " +
                        std::to_string(pairs) + " panel pairs, more than its 32-bit index allows (" +
                        std::to_string(std::numeric_limits<std::int32_t>::max()) +
                        "); use a coarser mesh (larger --max-edge)");
  // The exact size against the memory left now (the interior H-matrix is already held).
  require_memory(YukawaNearField<Scalar>::bytes_for(std::uint64_t(pairs), std::uint64_t(runs), n),
                 "the exterior near field of " + std::to_string(n) + " faces (" +
                     std::to_string(pairs) + " panel pairs)",
                 "use a coarser mesh (larger --max-edge)");
  YukawaNearField<Scalar> y;
  try {
    y = YukawaNearField<Scalar>(room);
  } catch (const std::bad_alloc&) {
    throw ran_out_of_memory(n);
  }
  GalerkinOperators<YukawaKernel> yukawa(YukawaKernel{kappa}, panels);
  yukawa.set_yukawa_accuracy(accuracy);
  yukawa.tabulate_touching_pairs();
  // At single-precision accuracy the near coplanar pairs below the diagonal (η < near_ratio:
  // the pairs whose outer rule takes the polar scheme's integrals; the others cost less than
  // the test) are mirrored (mirrored_coplanar_pair): marked NaN by the first pass, copied by
  // the second.
  const bool mirror = accuracy >= kSinglePrecisionRuleAccuracy;
  const auto mirrored = [&](Eigen::Index i, Eigen::Index j) {
    if (!mirror || j >= i) return false;
    const Panel& a = panels[size_t(perm[size_t(i)])];
    const Panel& b = panels[size_t(perm[size_t(j)])];
    const double near = OuterRuleThresholds::near_ratio * std::max(a.diameter, b.diameter);
    if ((a.centroid - b.centroid).squaredNorm() >= near * near) return false;
    return mirrored_coplanar_pair(a, b) &&
           yukawa.attenuated_points(a, b, GalerkinOperators<YukawaKernel>::separation_ratio(a, b)) == 0;
  };
  constexpr Scalar kMirrored = std::numeric_limits<Scalar>::quiet_NaN();

  std::atomic<Eigen::Index> rows_done{0};
#pragma omp parallel
  {
    std::vector<int> stack;
    std::vector<Eigen::Index> kept, faces;
    std::vector<std::size_t> computed;
    std::vector<GalerkinOperators<YukawaKernel>::Entry> entries;
    // Each row writes only its own slots, so the rows can be filled concurrently.
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index i = 0; i < n; ++i) {
      // A cancelled run skips the remaining rows (an exception cannot leave the parallel loop).
      if (cancellation_requested() || out_of_memory) continue;
      try {
        const Panel& test = panels[size_t(perm[size_t(i)])];
        row_columns(test, tree, cutoff, stack, kept);
        y.set_columns(i, kept);
        const Eigen::Index first = y.row_begin(i);
        faces.clear();
        computed.clear();
        for (size_t t = 0; t < kept.size(); ++t) {
          if (mirrored(i, kept[t])) {
            y.minus_double_layer()[first + Eigen::Index(t)] = Scalar(0);
            y.single_layer()[first + Eigen::Index(t)] = kMirrored;
          } else {
            faces.push_back(perm[size_t(kept[t])]);
            computed.push_back(t);
          }
        }
        entries.resize(faces.size());
        yukawa.fill_row(perm[size_t(i)], faces, entries);
        for (size_t u = 0; u < computed.size(); ++u) {
          const Eigen::Index slot = first + Eigen::Index(computed[u]);
          y.minus_double_layer()[slot] = static_cast<Scalar>(-entries[u].double_layer);
          y.single_layer()[slot] = static_cast<Scalar>(entries[u].single_layer);
        }
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
  if (mirror) {
    // The mirrored slots (i, j), j < i: Vκ[i, j] = Vκ[j, i] from row j (Kκ is 0 between
    // coplanar panels); computed here should row j not hold column i (the cutoff's test
    // rounds alike both ways, but is not required to).
#pragma omp parallel for schedule(dynamic, 64)
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Index s = y.row_begin(i);
      for (Eigen::Index r = y.run_begin(i); r < y.run_end(i); ++r)
        for (Eigen::Index j = y.run_column(r); j < y.run_column(r) + y.run_length(r); ++j, ++s) {
          if (!std::isnan(y.single_layer()[s])) continue;
          const Eigen::Index slot = y.slot(j, i);
          y.single_layer()[s] =
              slot >= 0 && !std::isnan(y.single_layer()[slot])
                  ? y.single_layer()[slot]
                  : static_cast<Scalar>(yukawa.entry(perm[size_t(i)], perm[size_t(j)]).single_layer);
        }
    }
  }
  return y;
}

template YukawaNearField<double> assemble_yukawa_near_field<double>(
    const std::vector<Panel>&, const ClusterTree&, double, double, const ProgressCallback&,
    const YukawaNearFieldRows*, double);
template YukawaNearField<float> assemble_yukawa_near_field<float>(
    const std::vector<Panel>&, const ClusterTree&, double, double, const ProgressCallback&,
    const YukawaNearFieldRows*, double);

}  // namespace bemshape::bem
