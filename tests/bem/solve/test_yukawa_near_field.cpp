// bem/solve/yukawa_near_field.hpp: the sparse exterior operator holds the dense path's
// entries of the pairs within the cutoff distance, to rounding (the neighbour search misses
// none), what it drops is about ε of each row's sum, and it is O(N): rows hold no more
// entries when the part grows.
#include <catch2/catch.hpp>

#include <cmath>

#include "bem/operators/galerkin_operators.hpp"
#include "bem/solve/yukawa_near_field.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

TEST_CASE("Yukawa near field: the dense operator's entries within the cutoff distance, nothing else") {
  // A plate 3.2 × 1.6 × 0.1 with κ = 10: the cutoff distance 2.3 reaches every panel on the
  // plate from its middle but not from the far ends.
  const auto mesh = geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3.2, 1.6, 0.1), 0.1);
  const double kappa = 10.0;
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 16);
  const bem::YukawaNearField<double> y = bem::assemble_yukawa_near_field(panels, tree, kappa);
  const bem::GalerkinOperators<bem::YukawaKernel> yukawa(bem::YukawaKernel{kappa}, panels);
  const Eigen::Index n = mesh.num_faces();
  REQUIRE(y.rows() == n);
  REQUIRE(y.cols() == 2 * n);
  const Eigen::MatrixXd sparse = y.to_dense();
  const auto& perm = tree.permutation();
  const double distance = bem::yukawa_cutoff_distance(kappa, bem::YukawaAttenuation::negligible);
  CHECK(distance == Approx(-std::log(1e-10) / kappa));
  // The attenuated pairs are computed 8 at a time (bem/operators/far_field_lanes.hpp), in another
  // order of summation: equal to rounding, 1e−13 of the entry or 1e−15 of the largest.
  const double largest = sparse.cwiseAbs().maxCoeff();
  const auto differ = [largest](double a, double b) {
    return std::abs(a - b) > 1e-13 * std::abs(b) + 1e-15 * largest;
  };
  Eigen::Index within = 0, mismatched = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const bem::Panel& test = panels[size_t(perm[size_t(i)])];
      const bem::Panel& trial = panels[size_t(perm[size_t(j)])];
      const bool kept =
          (test.centroid - trial.centroid).norm() - test.radius - trial.radius <= distance;
      const auto e = yukawa.entry(perm[size_t(i)], perm[size_t(j)]);
      within += kept;
      mismatched += differ(sparse(i, j), kept ? -e.double_layer : 0.0);
      mismatched += differ(sparse(i, n + j), kept ? e.single_layer : 0.0);
    }
  CHECK(mismatched == 0);
  // One pair per panel within the cutoff (every one has a nonzero single layer; Kκ's
  // coplanar zeros are stored with their Vκ), each row's columns strictly increasing; 16
  // bytes per pair in double precision and 6 per run of consecutive columns.
  CHECK(y.pairs() == within);
  Eigen::Index unsorted = 0, zero_single = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index previous = -1;
    y.for_each_in_row(i, [&](Eigen::Index j, double, double v) {
      unsorted += j <= previous;
      zero_single += v == 0.0;
      previous = j;
    });
  }
  CHECK(unsorted == 0);
  CHECK(zero_single == 0);
  CHECK(y.bytes() == 16 * std::uint64_t(y.pairs()) + 6 * std::uint64_t(y.runs()) + 16 * std::uint64_t(n + 1));
  // The runs are maximal: consecutive runs of a row never join up, and there are several
  // pairs per run (whole stretches of tree order lie within the cutoff).
  Eigen::Index joinable = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index r = y.run_begin(i) + 1; r < y.run_end(i); ++r)
      joinable += y.run_column(r) == y.run_column(r - 1) + y.run_length(r - 1);
  CHECK(joinable == 0);
  CHECK(y.pairs() > 4 * y.runs());
  CHECK(within < n * n);  // the cutoff drops something on this plate

  // The row sizes the memory guard counts before assembly: one pair per panel within the
  // cutoff, and their runs.
  const bem::YukawaNearFieldRows rows =
      bem::yukawa_near_field_rows(panels, tree, kappa, bem::YukawaAttenuation::negligible);
  REQUIRE(rows.pairs.size() == n);
  REQUIRE(rows.runs.size() == n);
  Eigen::Index wrong = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index single = 0, runs = 0;
    for (Eigen::Index j = 0; j < n; ++j) {
      single += sparse(i, n + j) != 0.0;
      runs += sparse(i, n + j) != 0.0 && (j == 0 || sparse(i, n + j - 1) == 0.0);
    }
    wrong += rows.pairs(i) != single;
    wrong += rows.pairs(i) != y.row_end(i) - y.row_begin(i);
    wrong += rows.runs(i) != runs;
    wrong += rows.runs(i) != y.run_end(i) - y.run_begin(i);
  }
  CHECK(wrong == 0);

  // The single-precision matrix of the H-matrix solver: the same pairs in the same runs,
  // each value the double one computed at the same accuracy (kSinglePrecisionYukawaAccuracy,
  // its default) rounded once to float, 8 bytes per pair.
  const bem::YukawaNearField<float> y_single = bem::assemble_yukawa_near_field<float>(panels, tree, kappa);
  const bem::YukawaNearField<double> y_coarse = bem::assemble_yukawa_near_field<double>(
      panels, tree, kappa, bem::YukawaAttenuation::negligible, {}, nullptr,
      bem::kSinglePrecisionYukawaAccuracy);
  REQUIRE(y_single.pairs() == y.pairs());
  REQUIRE(y_single.runs() == y.runs());
  REQUIRE(y_coarse.pairs() == y.pairs());
  CHECK(y_single.bytes() == 8 * std::uint64_t(y.pairs()) + 6 * std::uint64_t(y.runs()) + 16 * std::uint64_t(n + 1));
  Eigen::Index rounded_differently = 0;
  double largest_change = 0.0, largest_entry = 0.0;
  for (Eigen::Index r = 0; r < y.runs(); ++r)
    rounded_differently += y.run_column(r) != y_single.run_column(r) || y.run_length(r) != y_single.run_length(r);
  for (Eigen::Index s = 0; s < y.pairs(); ++s) {
    rounded_differently += static_cast<float>(y_coarse.minus_double_layer()[s]) != y_single.minus_double_layer()[s] ||
                           static_cast<float>(y_coarse.single_layer()[s]) != y_single.single_layer()[s];
    largest_change = std::max({largest_change, std::abs(y_coarse.single_layer()[s] - y.single_layer()[s]),
                               std::abs(y_coarse.minus_double_layer()[s] - y.minus_double_layer()[s])});
    largest_entry = std::max({largest_entry, std::abs(y.single_layer()[s]), std::abs(y.minus_double_layer()[s])});
  }
  CHECK(rounded_differently == 0);
  // The coarser entries differ from the full-accuracy ones by their accuracy (1e−7 of an
  // unattenuated entry), and the mirrored coplanar pairs by the difference of the two
  // orientations' outer rules (the near pairs' rules leave up to 6.4e−6 of a row's largest
  // V, docs/quadrature.md): 1.9e−6 here.
  CAPTURE(largest_change / largest_entry);
  CHECK(largest_change <= 1e-5 * largest_entry);
  CHECK(largest_change > 0.0);  // the mirrored pairs are the other orientation's
  // Near coplanar pairs (η < 2, not attenuated: the mirrored ones): Vκ exactly symmetric and
  // Kκ zero in the single-precision matrix.
  Eigen::Index coplanar = 0, asymmetric = 0;
  const auto& order = tree.permutation();
  for (Eigen::Index i = 0; i < n; ++i)
    y_single.for_each_in_row(i, [&](Eigen::Index j, double minus_k, double v) {
      const bem::Panel& a = panels[size_t(order[size_t(i)])];
      const bem::Panel& b = panels[size_t(order[size_t(j)])];
      const double ratio = yukawa.separation_ratio(a, b);
      if (!bem::mirrored_coplanar_pair(a, b) || ratio >= 2.0 || yukawa.attenuated_points(a, b, ratio) != 0)
        return;
      ++coplanar;
      const Eigen::Index back = y_single.slot(j, i);
      asymmetric += back < 0 || double(y_single.single_layer()[back]) != v || minus_k != 0.0;
    });
  CHECK(coplanar > n);
  CHECK(asymmetric == 0);
}

TEST_CASE("Yukawa near field: panels larger than the cutoff keep every neighbour they touch") {
  // A box of 0.5 elements with κ = 100: the cutoff 0.23 (ε = 1e−10) is below the distance
  // between the centroids of panels that share an edge or a corner (0.17–0.6), as on a
  // graded mesh whose flat walls take elements of several 1/κ. Every touching pair holds
  // the largest entries of its row; none may be dropped.
  const auto mesh = geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 1), 0.5);
  const double kappa = 100.0;
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 8);
  const bem::YukawaNearField<double> y = bem::assemble_yukawa_near_field(panels, tree, kappa);
  const Eigen::MatrixXd sparse = y.to_dense();
  const auto& perm = tree.permutation();
  const Eigen::Index n = mesh.num_faces();
  const double distance = bem::yukawa_cutoff_distance(kappa, bem::YukawaAttenuation::negligible);
  Eigen::Index touching = 0, beyond_centroid_cutoff = 0, dropped = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const bem::Panel& test = panels[size_t(perm[size_t(i)])];
      const bem::Panel& trial = panels[size_t(perm[size_t(j)])];
      bool shares_corner = false;
      for (const auto& a : test.corners)
        for (const auto& b : trial.corners) shares_corner = shares_corner || a == b;
      if (!shares_corner) continue;
      ++touching;
      beyond_centroid_cutoff += (test.centroid - trial.centroid).norm() > distance;
      dropped += sparse(i, n + j) == 0.0;
    }
  REQUIRE(beyond_centroid_cutoff > touching / 2);  // what the test is about
  CHECK(dropped == 0);
}

TEST_CASE("Yukawa near field: the dropped pairs are about the tolerance of each row's sum") {
  // A plate 1.6 × 1.6 × 0.1 with κ = 10 and a tolerance of 1e−3: R* = ln(1000)/κ = 0.69.
  // On a plane the part of ∫ Gκ dA beyond R* is e^{−κR*} = 1e−3 of the whole; the other
  // wall, 0.1 away, can add as much again, and the panel corners at R* round the disc
  // (yukawa_near_field.hpp).
  const auto mesh = geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.6, 1.6, 0.1), 0.1);
  const double kappa = 10.0, tolerance = 1e-3;
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 16);
  const bem::YukawaNearField<double> y = bem::assemble_yukawa_near_field(panels, tree, kappa, tolerance);
  const bem::GalerkinOperators<bem::YukawaKernel> yukawa(bem::YukawaKernel{kappa}, panels);
  const Eigen::Index n = mesh.num_faces();
  const Eigen::MatrixXd sparse = y.to_dense();
  const auto& perm = tree.permutation();
  double worst_single = 0.0, worst_double = 0.0;
  Eigen::Index dropping = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    double single = 0.0, single_dropped = 0.0, magnitude = 0.0, double_dropped = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) {
      const auto e = yukawa.entry(perm[size_t(i)], perm[size_t(j)]);
      single += e.single_layer;
      single_dropped += e.single_layer - sparse(i, n + j);
      // Kκ's row has both signs; its dropped part is judged against the row's magnitude.
      magnitude += std::abs(e.double_layer);
      double_dropped += std::abs(e.double_layer + sparse(i, j));
    }
    dropping += single_dropped > 0.0;
    worst_single = std::max(worst_single, single_dropped / single);
    worst_double = std::max(worst_double, double_dropped / magnitude);
  }
  CAPTURE(worst_single, worst_double);
  CHECK(dropping > n / 4);  // the cutoff does drop pairs in many rows
  CHECK(worst_single <= 2.0 * tolerance);
  CHECK(worst_single >= 0.1 * tolerance);  // and the bound is not idle
  CHECK(worst_double <= 2.0 * tolerance);
}

TEST_CASE("Yukawa near field: runs of consecutive columns, split at the longest run") {
  std::vector<Eigen::Index> columns;
  CHECK(bem::yukawa_near_field_runs(columns) == 0);
  columns = {3, 4, 5, 9, 11, 12};
  CHECK(bem::yukawa_near_field_runs(columns) == 3);
  // A stretch longer than kMaxRun is stored as several runs.
  const Eigen::Index longest = bem::YukawaNearField<float>::kMaxRun;
  columns.clear();
  for (Eigen::Index j = 0; j < 2 * longest + 5; ++j) columns.push_back(j);
  CHECK(bem::yukawa_near_field_runs(columns) == 3);
  bem::YukawaNearFieldRows rows{Eigen::VectorX<Eigen::Index>::Constant(1, Eigen::Index(columns.size())),
                                Eigen::VectorX<Eigen::Index>::Constant(1, 3)};
  bem::YukawaNearField<float> y(rows);
  y.set_columns(0, columns);
  CHECK(y.run_length(0) == longest);
  CHECK(y.run_column(1) == longest);
  CHECK(y.run_length(2) == 5);
  Eigen::Index expected = 0, wrong = 0;
  y.for_each_in_row(0, [&](Eigen::Index j, double, double) { wrong += j != expected++; });
  CHECK(wrong == 0);
  CHECK(expected == Eigen::Index(columns.size()));
}
