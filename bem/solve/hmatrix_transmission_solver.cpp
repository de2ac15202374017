#include "bem/solve/hmatrix_transmission_solver.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>

#include "bem/operators/galerkin_block_generator.hpp"
#include "linalg/gmres.hpp"
#include "bem/hmatrix/hierarchical_matrix.hpp"
#include "bem/hmatrix/nested_far_field.hpp"
#include "bem/solve/yukawa_near_field.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "core/memory_watch.hpp"
#include "core/number_text.hpp"
#include "core/solver_memory_refusal.hpp"

#include <omp.h>

namespace bemshape::bem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// With the far field nested (H²), for the memory estimate's bound: ranks per sheet of
/// surface a cluster holds (cluster_sheets). Measured (docs/reliability.md, "Estimate and
/// peak"): the H² part's bases and couplings of a 121680-face sphere match the count at a
/// rank of about 55, those of the 60120-face hollow box with walls of 0.1 (two sheets in
/// every cluster) at about 135, 68 per sheet; their largest ranks were 116 and 264. The
/// factored small blocks held 16 (sphere) and 26.6 (box, 13 per sheet) entries per block
/// edge entry.
constexpr double kNestedSheetRank = 80.0;
constexpr double kSmallBlockSheetRank = 20.0;
/// The most sheets a cluster is counted with: a corner of three walls reads 3.
constexpr double kMaxSheets = 4.0;
/// Near-field entries per panel of a single smooth sheet, per leaf panel (o·g = 2 per pair):
/// 622 per panel at leaves of 32 and η = 2 on the 121680-face sphere, 19.4 per leaf panel;
/// 1275 (2.05 sheets) on the 60120-face hollow box.
constexpr double kSingleSheetNearEntriesPerLeafPanel = 19.4;
/// Factor entries per entry of a block's edge o·|τ| + g·|σ| in the bound of the low-rank
/// blocks (HMatrixPartitionCounts::admissible_edges): the recompressed rank of the largest
/// blocks. Measured (docs/reliability.md, "Estimate and peak"): ...
constexpr double kBoundRank = 24.0;
/// Rank of a block's double-precision cross approximation while it is built (ACA's
/// overshoot is 16–21 % above the recompressed rank; the largest blocks' ranks stay below).
constexpr double kAcaWorkRank = 48.0;
/// Work arrays of one product with the three right-hand sides [bytes per face]: the
/// densities (n × 6), the row-major copy of x (2n × 3), the exterior rows (n × 3) and the
/// result (2n × 3), 8 bytes each, and the preconditioner's work on as many.
constexpr double kProductWorkBytes = 2.0 * 8.0 * (6.0 + 6.0 + 3.0 + 6.0);
/// The factor between the parts counted above and the process's peak growth measured over
/// the benchmark set (docs/reliability.md, "Estimate and peak"): the heap's retained and
/// fragmented pages, the nested far field's transient bases, the copies made while a part is
/// converted to its narrow format.
constexpr double kPeakSafetyFactor = 1.3;
/// The shortest restart length the memory guard may choose, below a user's longer one: above
/// the 13–22 iterations the fast path takes up to 10⁶ faces (docs/benchmarks.md).
constexpr int kMinRestart = 30;

using RowMajorRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Y·x for the exterior matrix in double or single precision (entries promoted to double),
/// x (2n × k) row-major so that each pair of row i reads the rows j (φ) and n + j (q) of x
/// once for all k vectors.
template <class Scalar>
RowMajorRows sparse_rows_product(const YukawaNearField<Scalar>& y, const RowMajorRows& x) {
  const Eigen::Index k = x.cols(), n = y.rows();
  RowMajorRows out = RowMajorRows::Zero(n, k);
  const Scalar* const minus_k = y.minus_double_layer();
  const Scalar* const v = y.single_layer();
#pragma omp parallel for schedule(static, 256)
  for (Eigen::Index i = 0; i < n; ++i) {
    double* const sums = out.data() + i * k;
    Eigen::Index s = y.row_begin(i);
    // A run's columns are consecutive: its rows of x are read as one contiguous stretch.
    // Three vectors (the three directions, the solver's case) are summed in registers.
    const auto add_row = [&](auto vectors) {
      constexpr int kv = decltype(vectors)::value;
      double acc[kv > 0 ? kv : 1] = {};
      for (Eigen::Index r = y.run_begin(i); r < y.run_end(i); ++r) {
        const double* phi = x.data() + y.run_column(r) * k;
        for (Eigen::Index t = 0; t < y.run_length(r); ++t, ++s, phi += k) {
          const double a = double(minus_k[s]), b = double(v[s]);
          const double* const q = phi + n * k;
          if constexpr (kv > 0) {
            for (int c = 0; c < kv; ++c) acc[c] += a * phi[c] + b * q[c];
          } else {
            for (Eigen::Index c = 0; c < k; ++c) sums[c] += a * phi[c] + b * q[c];
          }
        }
      }
      if constexpr (kv > 0)
        for (int c = 0; c < kv; ++c) sums[c] = acc[c];
    };
    if (k == 3)
      add_row(std::integral_constant<int, 3>{});
    else
      add_row(std::integral_constant<int, 0>{});
  }
  return out;
}

}  // namespace

FarFieldSplit split_far_field(const ClusterTree& tree, const std::vector<BlockIndex>& admissible,
                              const HMatrixSolverOptions& options) {
  // range[c]: the preconditioner block that contains cluster c, −1 above them.
  std::vector<int> range(tree.clusters().size(), -1);
  const std::vector<int> ranges = tree.clusters_up_to(options.preconditioner_block);
  for (std::size_t r = 0; r < ranges.size(); ++r) {
    std::vector<int> stack{ranges[r]};
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      range[std::size_t(c)] = int(r);
      if (!tree.cluster(c).is_leaf())
        stack.insert(stack.end(), {tree.cluster(c).first_child, tree.cluster(c).first_child + 1});
    }
  }
  FarFieldSplit split;
  for (const BlockIndex& b : admissible) {
    const bool large = std::min(tree.cluster(b.rows).size(), tree.cluster(b.cols).size()) >=
                       options.nested_min_cluster;
    const bool in_one_block = range[std::size_t(b.rows)] >= 0 &&
                              range[std::size_t(b.rows)] == range[std::size_t(b.cols)];
    (large && !in_one_block ? split.nested : split.factored).push_back(b);
  }
  return split;
}

std::vector<double> cluster_sheets(const ClusterTree& tree, const std::vector<Panel>& panels) {
  // Panels' areas summed over tree positions, then over each cluster's range.
  const auto& perm = tree.permutation();
  std::vector<double> prefix(perm.size() + 1, 0.0);
  for (std::size_t p = 0; p < perm.size(); ++p) prefix[p + 1] = prefix[p] + panels[perm[p]].area;
  std::vector<double> sheets(tree.clusters().size(), 1.0);
  for (std::size_t c = 0; c < sheets.size(); ++c) {
    const Cluster& cluster = tree.cluster(int(c));
    Eigen::Vector3d extent = cluster.box.hi - cluster.box.lo;
    std::sort(extent.data(), extent.data() + 3);
    const double footprint = extent(2) * extent(1);
    const double area = prefix[std::size_t(cluster.end)] - prefix[std::size_t(cluster.begin)];
    sheets[c] = footprint > 0.0 ? std::clamp(area / footprint, 1.0, kMaxSheets) : 1.0;
  }
  return sheets;
}

HMatrixPartitionCounts count_partition(const ClusterTree& tree, const BlockPartition& partition,
                                       const std::vector<Panel>& panels,
                                       const HMatrixSolverOptions& options) {
  // The Laplace row's generator: one output per row panel, two densities (φ, q) per column.
  constexpr double o = 1.0, g = 2.0;
  const auto size = [&](int c) { return double(tree.cluster(c).size()); };
  const auto edge = [&](const BlockIndex& b) { return o * size(b.rows) + g * size(b.cols); };
  HMatrixPartitionCounts counts;
  for (const BlockIndex& b : partition.dense)
    counts.near_entries += o * size(b.rows) * g * size(b.cols);
  for (const BlockIndex& b : partition.admissible) {
    counts.admissible_edges += edge(b);
    counts.largest_admissible_edge = std::max(counts.largest_admissible_edge, edge(b));
  }

  // Sheets per cluster: its own (cluster_sheets), and at least those the near field reads
  // over the whole surface, its entries per panel over a single smooth sheet's. The first
  // sees both skins where a cluster holds them; the second where a wall's other skin is in
  // the clusters beside it, which the ranks of its blocks see as well (on the 60120-face box
  // the clusters' own read fewer sheets than its ranks show, on a 6168-face box with walls
  // thinner than an edge the near field reads fewer: docs/reliability.md, "Estimate and
  // peak"). The solver splits the blocks again when it builds the H² part (split_far_field:
  // one pass over the admissible blocks, small beside the counting of the exterior pairs).
  std::vector<double> sheets = cluster_sheets(tree, panels);
  const double near_sheets = std::clamp(
      counts.near_entries / (double(tree.root().size()) * kSingleSheetNearEntriesPerLeafPanel *
                             double(options.leaf_size)),
      1.0, kMaxSheets);
  for (double& s : sheets) s = std::max(s, near_sheets);
  const auto block_sheets = [&](const BlockIndex& b) {
    return std::max(sheets[std::size_t(b.rows)], sheets[std::size_t(b.cols)]);
  };
  const FarFieldSplit split = split_far_field(tree, partition.admissible, options);
  for (const BlockIndex& b : split.factored)
    counts.factored_rank_edges += kSmallBlockSheetRank * block_sheets(b) * edge(b);
  // The H² part: a basis on every cluster inside a nested block's cluster, on each side, of
  // rank k_t = kNestedSheetRank·sheets(t), never more than the cluster's rows (o|t| on the
  // row side, g|t| on the column side). Leaves hold d|t| × k_t, inner clusters
  // (k_t₁ + k_t₂) × k_t; a coupling is k_τ × k_σ.
  const auto rank = [&](int c, double d) {
    return std::min(kNestedSheetRank * sheets[std::size_t(c)], d * size(c));
  };
  for (const double d : {o, g}) {
    std::vector<char> has_basis(tree.clusters().size(), 0);
    std::vector<int> stack;
    for (const BlockIndex& b : split.nested) stack.push_back(d == o ? b.rows : b.cols);
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      if (has_basis[std::size_t(c)]) continue;
      has_basis[std::size_t(c)] = 1;
      const Cluster& cluster = tree.cluster(c);
      if (cluster.is_leaf()) {
        counts.nested_basis_entries += d * size(c) * rank(c, d);
      } else {
        counts.nested_basis_entries +=
            (rank(cluster.first_child, d) + rank(cluster.first_child + 1, d)) * rank(c, d);
        stack.insert(stack.end(), {cluster.first_child, cluster.first_child + 1});
      }
    }
  }
  for (const BlockIndex& b : split.nested)
    counts.nested_coupling_entries += rank(b.rows, o) * rank(b.cols, g);
  return counts;
}

std::uint64_t hmatrix_solver_memory_estimate(Eigen::Index faces, std::uint64_t exterior_pairs,
                                             std::uint64_t exterior_runs,
                                             const HMatrixSolverOptions& options,
                                             HMatrixSolverOptions::FarField far_field,
                                             const HMatrixPartitionCounts& counts,
                                             std::uint64_t held_bytes) {
  if (far_field == HMatrixSolverOptions::FarField::automatic)
    far_field = options.far_field == HMatrixSolverOptions::FarField::nested
                    ? HMatrixSolverOptions::FarField::nested
                    : HMatrixSolverOptions::FarField::hmatrix;
  const double n = double(faces);
  // The near field exactly, 4 or 8 bytes an entry; factor entries take 8 bytes in double
  // precision, 2.5 on average in single precision with the fixed-point columns (measured:
  // 2.27 on a 100820-face sphere, 2.49 on a remeshed 121480-face box;
  // AdaptivePrecisionFactors), at a bounding rank per block edge entry.
  const double entry_bytes = options.single_precision ? 4.0 : 8.0;
  const double factor_bytes = options.single_precision ? 2.5 : 8.0;
  const double near = entry_bytes * counts.near_entries;
  // Nested: the factored blocks at kSmallBlockSheetRank per sheet, and the H² part's bases,
  // transfer matrices and couplings as counted, 4 bytes an entry.
  const double far =
      far_field == HMatrixSolverOptions::FarField::nested
          ? factor_bytes * counts.factored_rank_edges +
                4.0 * (counts.nested_basis_entries + counts.nested_coupling_entries)
          : factor_bytes * kBoundRank * counts.admissible_edges;
  // Yukawa: written in place, its values in the factors' precision.
  const double yukawa =
      double(options.single_precision
                 ? YukawaNearField<float>::bytes_for(exterior_pairs, exterior_runs, faces)
                 : YukawaNearField<double>::bytes_for(exterior_pairs, exterior_runs, faces));
  const double preconditioner =
      double(ClusterBlockPreconditioner::bytes_for(faces, options.preconditioner_block));
  // The coarse space: A_c and its LU for at most kMaxClusters clusters, both held while the
  // LU is computed (only the LU is kept; A E's factors are small beside the preconditioner's).
  const double clusters = options.coarse_cluster > 0
                              ? std::min(double(ClusterCoarseSpace::kMaxClusters),
                                         n / (0.5 * double(options.coarse_cluster)))
                              : 0.0;
  const double coarse = 16.0 * 4.0 * clusters * clusters;
  // Three Krylov bases (one per direction, solved in lockstep) and their work vectors, and
  // the product's copies of the three right-hand sides (densities, row-major copy, exterior
  // rows, result: kProductWorkBytes per face).
  const double krylov = 3.0 * 8.0 * 2.0 * n * (options.restart + 6.0) + kProductWorkBytes * n;
  // Each thread's cross approximation holds its block's factors in double precision at up
  // to kAcaWorkRank before they are recompressed and narrowed.
  const double threads = double(std::max(1, omp_get_max_threads()));
  const double aca_work = threads * 2.0 * 8.0 * kAcaWorkRank * counts.largest_admissible_edge;
  return held_bytes + static_cast<std::uint64_t>(
                          kPeakSafetyFactor *
                          (near + far + yukawa + preconditioner + coarse + krylov + aca_work));
}

std::uint64_t hmatrix_solver_minimum_bytes(Eigen::Index faces,
                                           const HMatrixSolverOptions& options) {
  const double n = double(faces);
  return ClusterBlockPreconditioner::bytes_for(faces, options.preconditioner_block) +
         static_cast<std::uint64_t>(3.0 * 8.0 * 2.0 * n * (kMinRestart + 6.0));
}

BoundarySolution solve_transmission_hmatrix(const geometry::SurfaceMesh& mesh,
                                            const TransmissionParameters& parameters,
                                            const HMatrixSolverOptions& options,
                                            const ProgressCallback& progress) {
  const Eigen::Index n = mesh.num_faces();
  if (n == 0) throw InputError("the mesh has no faces");
  const auto start = Clock::now();
  const std::vector<Panel> panels = make_panels(mesh);
  const ClusterTree tree(panels, options.leaf_size);
  const auto& perm = tree.permutation();
  // Exterior pairs whose centroids are farther apart than 18.4/κ (−ln ε/κ at the default
  // ε = 1e−8) are dropped: about ε of each row's sum, the relative accuracy the compression
  // of the Laplace part works to (bem/solve/yukawa_near_field.hpp). The dense path
  // keeps more (entries down to 1e−10 of an unattenuated one); on the benchmarks' sphere and
  // thin-walled box the two agree to the digits docs/benchmarks.md lists. Their exact count,
  // before anything is assembled, goes into the memory guard: it varies with κ·h and with
  // the walls' thickness far more than the Laplace part does.
  const double negligible = options.aca_tolerance;
  const auto count_start = Clock::now();
  const YukawaNearFieldRows exterior_rows =
      yukawa_near_field_rows(panels, tree, parameters.kappa, negligible);
  const double count_seconds = seconds_since(count_start);
  using FarField = HMatrixSolverOptions::FarField;
  BlockPartition partition = partition_blocks(tree, options.eta);
  const HMatrixPartitionCounts counts = count_partition(tree, partition, panels, options);
  // What the process holds already (meshes, panels, tree, partition) is part of the peak;
  // the budget is the resident size the run may reach (core/memory_watch.hpp).
  const std::uint64_t held = options.held_bytes.value_or(process_memory().resident);
  const auto estimate = [&](const HMatrixSolverOptions& o, FarField far_field) {
    return hmatrix_solver_memory_estimate(n, std::uint64_t(exterior_rows.pairs.sum()),
                                          std::uint64_t(exterior_rows.runs.sum()), o, far_field,
                                          counts, held);
  };
  std::string budget_reason;
  const std::uint64_t budget =
      resident_memory_limit_bytes(options.max_memory_bytes, &budget_reason);
  FarField far_field = options.far_field;
  if (far_field == FarField::automatic) {
    const std::uint64_t factored = estimate(options, FarField::hmatrix);
    // Below a few levels of large clusters the H² form saves nothing (the estimate knows);
    // its bases and couplings are in single precision, which a tolerance below 1e−6 rules
    // out (single_precision off).
    far_field = budget == 0 || factored <= budget || !options.single_precision ||
                        factored <= estimate(options, FarField::nested)
                    ? FarField::hmatrix
                    : FarField::nested;
  }
  if (far_field == FarField::nested && !options.single_precision) {
    throw InputError(
        "the far field in the H² form (--far-field nested) is stored in single precision, "
        "which perturbs a product by about 1e-7: use --tolerance 1e-6 or larger with it, or "
        "--far-field hmatrix");
  }
  // The Krylov bases take 48·N bytes per step of the restart length. Where the whole does
  // not fit, a shorter restart is taken, down to kMinRestart: GMRES(m) is full GMRES for its
  // first m iterations, and the solver needs 13–22 (docs/benchmarks.md).
  HMatrixSolverOptions fitted = options;
  while (budget > 0 && fitted.restart > kMinRestart && estimate(fitted, far_field) > budget)
    fitted.restart = std::max(kMinRestart, fitted.restart - 10);
  const std::uint64_t needed = estimate(fitted, far_field);
  const std::string what = "the hierarchical-matrix BEM system of " + std::to_string(n) + " faces";
  // The other form of the far field, where it would need less, is a way out too.
  const bool nested_smaller =
      far_field == FarField::hmatrix && options.single_precision &&
      estimate(fitted, FarField::nested) < needed;
  // A larger limit helps where it is the user's: --max-memory or ulimit -v.
  const std::string larger_limit = budget_reason == " (ulimit -v)"      ? " or a larger ulimit -v"
                                   : budget_reason == " (--max-memory)" ? " or a larger --max-memory"
                                                                        : "";
  const std::string instead = std::string("use a coarser mesh (larger --max-edge)") +
                              (nested_smaller ? ", --far-field nested" : "") + larger_limit;
  if (budget > 0 && needed > budget)
    throw SolverMemoryRefusal(what + " needs " + number_text(double(needed) / 1e9, 3) +
                                  " GB (estimated peak of the process) but only " +
                                  number_text(double(budget) / 1e9, 3) + " GB may be used" +
                                  budget_reason + "; " + instead,
                              SolverMemoryRefusal::Solver::hmatrix, long(n), double(needed),
                              double(budget), double(held));
  set_memory_context(what + " (estimated peak " + number_text(double(needed) / 1e9, 3) + " GB)",
                     instead);
  if (options.estimate_only) {
    BoundarySolution estimated;
    estimated.parameters = parameters;
    estimated.report.memory_estimate_bytes = needed;
    estimated.report.unknowns = 2 * n;
    return estimated;
  }

  report_progress(progress, "assemble", 0.0);
  const auto interior_start = Clock::now();
  // The entries are computed to what the run keeps of them: stored in single precision for a
  // solve to 1e−6 or coarser (the default), to kSinglePrecisionRuleAccuracy (cheaper Gauss
  // rules and polar resolutions, docs/quadrature.md); otherwise to the full accuracy of the
  // panel integrals, so that a tighter tolerance is not limited by them.
  const bool single_precision_entries =
      options.single_precision && options.tolerance >= kSinglePrecisionEntriesTolerance;
  const double yukawa_accuracy = single_precision_entries ? kSinglePrecisionYukawaAccuracy
                                                          : YukawaAttenuation::absolute_accuracy;
  // The blocks of the H² part: between clusters of at least nested_min_cluster panels, and
  // not inside one preconditioner block (the preconditioner reads its blocks from the
  // H-matrix, HierarchicalMatrix::diagonal_blocks).
  std::vector<BlockIndex> nested_blocks;
  if (far_field == FarField::nested) {
    FarFieldSplit split = split_far_field(tree, partition.admissible, options);
    nested_blocks = std::move(split.nested);
    partition.admissible = std::move(split.factored);
  }
  // The generator (tree-ordered panels, their arrays, the touching pairs' table: about
  // 0.65 kB per panel) is released as soon as the blocks are built. The H² part comes first:
  // the memory its construction holds for a while is then reused by what follows.
  std::optional<NestedFarField> far;
  double far_seconds = 0.0;
  const HierarchicalMatrix laplace = [&] {
    const GalerkinBlockGenerator<LaplaceKernel> generator(LaplaceKernel{}, panels,
                                                          tree.permutation(),
                                                          single_precision_entries);
    if (!nested_blocks.empty()) {
      const auto far_start = Clock::now();
      NestedFarFieldOptions far_options;
      far_options.aca_tolerance = options.aca_tolerance;
      far.emplace(tree, nested_blocks, generator, far_options, progress);
      partition.dense.insert(partition.dense.end(), far->uncompressed().begin(),
                             far->uncompressed().end());
      far_seconds = seconds_since(far_start);
    }
    return HierarchicalMatrix(
        tree, tree, partition, generator,
        {options.aca_tolerance, options.eta, options.single_precision, options.single_precision},
        progress);
  }();
  const double interior_seconds = seconds_since(interior_start);
  throw_if_cancelled();  // the memory watch may have stopped the run (core/memory_watch.hpp)
  report_progress(progress, "assemble exterior", 0.0);
  const auto exterior_start = Clock::now();
  // In single precision with the factors (12 bytes per pair instead of 20); one of the two
  // is assembled, and with_exterior hands it to the code that reads it.
  const YukawaNearField<double> yukawa_double =
      options.single_precision ? YukawaNearField<double>()
                               : assemble_yukawa_near_field<double>(panels, tree, parameters.kappa,
                                                                    negligible, progress, &exterior_rows,
                                                                    yukawa_accuracy);
  const YukawaNearField<float> yukawa_single =
      options.single_precision ? assemble_yukawa_near_field<float>(panels, tree, parameters.kappa,
                                                                   negligible, progress, &exterior_rows,
                                                                   yukawa_accuracy)
                               : YukawaNearField<float>();
  const auto with_exterior = [&](const auto& use) {
    return options.single_precision ? use(yukawa_single) : use(yukawa_double);
  };
  const double exterior_seconds = count_seconds + seconds_since(exterior_start);
  Eigen::VectorXd half_mass(n);
  for (Eigen::Index p = 0; p < n; ++p) half_mass(p) = 0.5 * mesh.face_areas()(perm[size_t(p)]);
  throw_if_cancelled();
  report_progress(progress, "preconditioner", 0.0);
  const ClusterBlockPreconditioner preconditioner = with_exterior([&](const auto& yukawa) {
    return ClusterBlockPreconditioner(tree, laplace, yukawa, half_mass, options.preconditioner_block);
  });
  std::optional<ClusterCoarseSpace> coarse;
  if (options.coarse_cluster > 0)
    with_exterior([&](const auto& yukawa) {
      coarse.emplace(tree, laplace, yukawa, half_mass, options.coarse_cluster,
                     HierarchicalMatrix::GroupedColumns::Storage::fixed8, far ? &*far : nullptr);
    });

  throw_if_cancelled();
  BoundarySolution solution;
  solution.parameters = parameters;
  solution.report.memory_estimate_bytes = needed;
  solution.report.method = far ? "hmatrix-h2-gmres" : "hmatrix-gmres";
  solution.report.unknowns = 2 * n;
  solution.report.restart = fitted.restart;
  solution.report.assembly_seconds = seconds_since(start);
  // The interior H-matrix's wall time split between its dense (near-field) and low-rank
  // (far-field) blocks in proportion to the thread time each kind took.
  const HierarchicalMatrixStats& hstats = laplace.stats();
  const double block_seconds = hstats.dense_seconds + hstats.low_rank_seconds;
  const double near_share = block_seconds > 0.0 ? hstats.dense_seconds / block_seconds : 0.0;
  const double hmatrix_seconds = interior_seconds - far_seconds;
  solution.report.assembly_stages = {
      {"interior near field", near_share * hmatrix_seconds},
      {"interior far field", (1.0 - near_share) * hmatrix_seconds + far_seconds},
      {"exterior near field", exterior_seconds},
      {"preconditioner", solution.report.assembly_seconds - interior_seconds - exterior_seconds}};
  solution.report.operator_parts = {
      {"interior near field", hstats.dense_bytes},
      {"interior far field", hstats.low_rank_bytes + (far ? far->stats().bytes : 0)},
      {"exterior near field", with_exterior([](const auto& yukawa) { return yukawa.bytes(); })},
      {"preconditioner", preconditioner.bytes() + (coarse ? coarse->bytes() : 0)}};
  for (const auto& [part, bytes] : solution.report.operator_parts)
    solution.report.operator_bytes += bytes;
  // Stored over dense entries of the Laplace row, the H² part's bases and couplings included.
  solution.report.compression =
      hstats.full_entries > 0
          ? double(hstats.dense_entries + hstats.low_rank_entries +
                   (far ? far->stats().leaf_basis_entries + far->stats().transfer_entries +
                              far->stats().coupling_entries
                        : 0)) /
                double(hstats.full_entries)
          : 0.0;

  // The three directions share the operator: their GMRES run in lockstep (gmres_columns),
  // so each step reads the H-matrix, the sparse exterior matrix and the preconditioner's
  // factors once for all three vectors. x, y: 2n × k, one column per direction.
  using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  double interior_product_seconds = 0.0, exterior_product_seconds = 0.0,
         preconditioner_seconds = 0.0;
  const auto system = [&](const Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
    const auto interior_start = Clock::now();
    const Eigen::Index k = x.cols();
    y.resize(2 * n, k);
    Eigen::MatrixXd densities(n, 2 * k);  // column 2j: φ of vector j, 2j + 1: its q
    for (Eigen::Index j = 0; j < k; ++j) {
      densities.col(2 * j) = x.col(j).head(n);
      densities.col(2 * j + 1) = x.col(j).tail(n);
    }
    y.topRows(n).noalias() = -(half_mass.asDiagonal() * x.topRows(n));
    laplace.multiply_add(densities, y.topRows(n));
    if (far)
      far->multiply_add(densities, y.topRows(n));
    const auto exterior_start = Clock::now();
    interior_product_seconds += seconds_since(interior_start);
    // A row-major right-hand side lets the sparse product read each row once for all k.
    const RowMajorMatrix x_rows = x;
    const RowMajorMatrix exterior =
        with_exterior([&](const auto& yukawa) { return sparse_rows_product(yukawa, x_rows); });
    y.bottomRows(n) = half_mass.asDiagonal() * x.topRows(n) + exterior;
    exterior_product_seconds += seconds_since(exterior_start);
  };
  const auto precondition = [&](const Eigen::MatrixXd& r, Eigen::MatrixXd& z) {
    const auto start = Clock::now();
    if (coarse)
      coarse->apply_two_level(preconditioner, r, z);
    else
      preconditioner.apply(r, z);
    preconditioner_seconds += seconds_since(start);
  };

  const auto solve_start = Clock::now();
  linalg::GmresOptions gmres_options;
  gmres_options.tolerance = options.tolerance;
  gmres_options.restart = fitted.restart;
  gmres_options.max_iterations = options.max_iterations;
  gmres_options.side = options.preconditioner_side;
  // b = (0, Vκ g) per direction i: the single-layer half of Y applied to g = n_i/ã.
  RowMajorMatrix g = RowMajorMatrix::Zero(2 * n, 3);
  for (Eigen::Index p = 0; p < n; ++p)
    g.row(n + p) = mesh.face_normals().row(perm[size_t(p)]) / parameters.a_tilde;
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(2 * n, 3);
  b.bottomRows(n) = with_exterior([&](const auto& yukawa) { return sparse_rows_product(yukawa, g); });
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(2 * n, 3);
  std::array<int, 3> reached{0, 0, 0};
  const std::vector<linalg::GmresResult> results = linalg::gmres_columns(
      system, precondition, b, x, gmres_options, [&](int direction, int iteration, double) {
        throw_if_cancelled();  // called between GMRES steps, outside parallel regions
        reached[size_t(direction)] = iteration;
        double done = 0.0;
        for (const int r : reached) done += std::min(1.0, r / 30.0) / 3.0;
        report_progress(progress, "solve", done);
      });
  solution.phi.resize(n, 3);
  solution.q.resize(n, 3);
  for (int i = 0; i < 3; ++i) {
    const linalg::GmresResult& result = results[size_t(i)];
    solution.report.iterations = std::max(solution.report.iterations, result.iterations);
    solution.report.residual = std::max(solution.report.residual, result.residual);
    solution.report.preconditioned_residual =
        std::max(solution.report.preconditioned_residual, result.preconditioned_residual);
    if (!result.converged || !x.col(i).allFinite()) {
      std::ostringstream msg;
      msg << "hierarchical-matrix BEM solve (direction " << i + 1 << "): GMRES reached relative "
          << (options.preconditioner_side == linalg::PreconditionerSide::left ? "preconditioned " : "")
          << "residual " << result.preconditioned_residual << " after " << result.iterations
          << " iterations, tolerance " << options.tolerance;
      if (fitted.restart < options.restart)
        msg << " (GMRES restarted every " << fitted.restart << " steps instead of "
            << options.restart << " to fit in memory)";
      msg << "; check the mesh for badly shaped faces or use --solver dense on a coarser mesh";
      throw NumericalError(msg.str());
    }
    for (Eigen::Index p = 0; p < n; ++p) {
      solution.phi(perm[size_t(p)], i) = x(p, i);
      solution.q(perm[size_t(p)], i) = x(n + p, i);
    }
  }
  report_progress(progress, "solve", 1.0);
  solution.report.solve_seconds = seconds_since(solve_start);
  solution.report.solve_stages = {
      {"interior product", interior_product_seconds},
      {"exterior product", exterior_product_seconds},
      {"preconditioner", preconditioner_seconds},
      {"Krylov and the rest", solution.report.solve_seconds - interior_product_seconds -
                     exterior_product_seconds - preconditioner_seconds}};
  return solution;
}

}  // namespace bemshape::bem
