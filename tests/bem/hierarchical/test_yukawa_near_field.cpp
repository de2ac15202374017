// bem/hierarchical/yukawa_near_field.hpp: the sparse exterior operator holds the dense path's
// entries, to rounding (the neighbour search misses none, the dropping rule is the same) and
// is O(N): rows hold no more entries when the part grows.
#include <catch2/catch.hpp>

#include <cmath>

#include "bem/galerkin_operators.hpp"
#include "bem/hierarchical/yukawa_near_field.hpp"
#include "bem/yukawa_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

TEST_CASE("Yukawa near field: every nonzero entry of the dense operator, nothing else") {
  // A plate 1.6 × 1.6 × 0.1 with κ = 10: the cutoff gap 2.3 reaches every panel on the
  // plate from its middle but not from the far corners.
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
  // The attenuated pairs are computed 8 at a time (bem/far_field_lanes.hpp), in another
  // order of summation: equal to rounding, 1e−13 of the entry or 1e−15 of the largest.
  const double largest = sparse.cwiseAbs().maxCoeff();
  const auto differ = [largest](double a, double b) {
    return std::abs(a - b) > 1e-13 * std::abs(b) + 1e-15 * largest;
  };
  Eigen::Index nonzero = 0, mismatched = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const auto e = yukawa.entry(perm[size_t(i)], perm[size_t(j)]);
      nonzero += e.single_layer != 0.0;
      mismatched += differ(sparse(i, j), -e.double_layer);
      mismatched += differ(sparse(i, n + j), e.single_layer);
    }
  CHECK(mismatched == 0);
  // One pair per panel with a nonzero single layer (Kκ's coplanar zeros are stored with
  // their Vκ), each row's columns strictly increasing, 20 bytes per pair in double
  // precision.
  CHECK(y.pairs() == nonzero);
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
  CHECK(y.bytes() == 20 * std::uint64_t(y.pairs()) + 8 * std::uint64_t(n + 1));
  CHECK(nonzero < n * n);  // the cutoff drops something on this plate

  // The row sizes the memory guard counts before assembly: one pair per panel with a
  // nonzero single-layer entry (every panel within the cutoff has one).
  const Eigen::VectorX<Eigen::Index> pairs =
      bem::yukawa_near_field_row_pairs(panels, tree, kappa, bem::YukawaAttenuation::negligible);
  REQUIRE(pairs.size() == n);
  Eigen::Index wrong = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index single = 0;
    for (Eigen::Index j = 0; j < n; ++j) single += sparse(i, n + j) != 0.0;
    wrong += pairs(i) != single;
    wrong += pairs(i) != y.row_end(i) - y.row_begin(i);
  }
  CHECK(wrong == 0);

  // The single-precision matrix of the H-matrix solver: the same pairs, each value the
  // double one rounded once to float, 12 bytes per pair.
  const bem::YukawaNearField<float> y_single = bem::assemble_yukawa_near_field<float>(panels, tree, kappa);
  REQUIRE(y_single.pairs() == y.pairs());
  CHECK(y_single.bytes() == 12 * std::uint64_t(y.pairs()) + 8 * std::uint64_t(n + 1));
  Eigen::Index rounded_differently = 0;
  for (Eigen::Index s = 0; s < y.pairs(); ++s)
    rounded_differently += y.column()[s] != y_single.column()[s] ||
                           static_cast<float>(y.minus_double_layer()[s]) != y_single.minus_double_layer()[s] ||
                           static_cast<float>(y.single_layer()[s]) != y_single.single_layer()[s];
  CHECK(rounded_differently == 0);
}
