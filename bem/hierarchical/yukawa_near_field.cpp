#include "bem/hierarchical/yukawa_near_field.hpp"

#include <atomic>
#include <cstdint>
#include <limits>
#include <new>
#include <string>
#include <cmath>
#include <vector>

#include "bem/galerkin_operators.hpp"
#include "bem/yukawa_kernel.hpp"
#include "core/errors.hpp"
#include "core/cancellation.hpp"

namespace bemshape::bem {

double yukawa_cutoff_gap(double kappa, double negligible) { return -std::log(negligible) / kappa; }

SparseRowMatrix assemble_yukawa_near_field(const std::vector<Panel>& panels,
                                           const ClusterTree& tree, double kappa,
                                           double negligible, const ProgressCallback& progress) {
  const GalerkinOperators<YukawaKernel> yukawa(YukawaKernel{kappa}, panels);
  const auto& perm = tree.permutation();
  const Eigen::Index n = tree.root().size();
  double max_radius = 0.0;
  for (const Panel& p : panels) max_radius = std::max(max_radius, p.radius);
  // The dense path drops an entry when gap = |c_j − c_k| − r_j − r_k > g*; the distance of
  // the boxes around the panels is at most |c_j − c_k|, so clusters farther than
  // g* + 2·max radius hold no kept entry.
  const double cutoff = yukawa_cutoff_gap(kappa, negligible);
  const double reach = cutoff + 2.0 * max_radius;

  std::vector<std::vector<std::int32_t>> columns(static_cast<size_t>(n));
  std::vector<std::vector<double>> values(static_cast<size_t>(n));
  std::atomic<Eigen::Index> rows_done{0};
  std::atomic<bool> out_of_memory{false};
#pragma omp parallel for schedule(dynamic, 16)
  for (Eigen::Index i = 0; i < n; ++i) {
    // A cancelled run skips the remaining rows (an exception cannot leave the parallel loop).
    if (cancellation_requested() || out_of_memory) continue;
    try {
      const Panel& test = panels[size_t(perm[size_t(i)])];
      BoundingBox box;
      for (const auto& c : test.corners) box.extend(c);
      std::vector<Eigen::Index> near;  // tree positions of the candidate trial panels
      std::vector<int> stack{0};
      while (!stack.empty()) {
        const Cluster& cl = tree.cluster(stack.back());
        stack.pop_back();
        if (box.distance(cl.box) > reach) continue;
        if (cl.is_leaf()) {
          for (Eigen::Index j = cl.begin; j < cl.end; ++j) near.push_back(j);
        } else {
          stack.push_back(cl.first_child + 1);
          stack.push_back(cl.first_child);
        }
      }
      std::sort(near.begin(), near.end());
      auto& cols = columns[size_t(i)];
      auto& vals = values[size_t(i)];
      std::vector<std::pair<std::int32_t, double>> single;
      for (const Eigen::Index j : near) {
        const Panel& trial = panels[size_t(perm[size_t(j)])];
        if ((test.centroid - trial.centroid).norm() - test.radius - trial.radius > cutoff) continue;
        const auto e = yukawa.entry(perm[size_t(i)], perm[size_t(j)]);
        if (e.double_layer != 0.0) {
          cols.push_back(static_cast<std::int32_t>(j));
          vals.push_back(-e.double_layer);
        }
        if (e.single_layer != 0.0) single.emplace_back(static_cast<std::int32_t>(n + j), e.single_layer);
      }
      for (const auto& [c, v] : single) {
        cols.push_back(c);
        vals.push_back(v);
      }
    } catch (const std::bad_alloc&) {
      out_of_memory = true;  // reported after the loop: an exception cannot leave it
    }
    const Eigen::Index done = ++rows_done;
    if (progress && done % 1024 == 0) {
#pragma omp critical(bemshape_progress)
      report_progress(progress, "assemble exterior", double(done) / double(n));
    }
  }
  throw_if_cancelled();
  if (out_of_memory)
    throw ResourceError("the exterior near field of " + std::to_string(n) +
                        " faces ran out of memory while assembling; use a coarser mesh "
                        "(larger --max-edge)");
  SparseRowMatrix y(n, 2 * n);
  Eigen::VectorX<Eigen::Index> counts(n);
  Eigen::Index total = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    counts(i) = static_cast<Eigen::Index>(columns[size_t(i)].size());
    total += counts(i);
  }
  if (total > std::numeric_limits<std::int32_t>::max())
    throw ResourceError("the exterior near field of " + std::to_string(n) + " faces has " +
                        std::to_string(total) + " entries, more than its 32-bit index allows (" +
                        std::to_string(std::numeric_limits<std::int32_t>::max()) +
                        "); use a coarser mesh (larger --max-edge)");
  y.reserve(counts);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (size_t k = 0; k < columns[size_t(i)].size(); ++k)
      y.insert(i, columns[size_t(i)][k]) = values[size_t(i)][k];
    std::vector<std::int32_t>().swap(columns[size_t(i)]);
    std::vector<double>().swap(values[size_t(i)]);
  }
  y.makeCompressed();
  return y;
}

}  // namespace bemshape::bem
