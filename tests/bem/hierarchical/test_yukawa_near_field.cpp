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
  const bem::SparseRowMatrix y = bem::assemble_yukawa_near_field(panels, tree, kappa);
  const bem::GalerkinOperators<bem::YukawaKernel> yukawa(bem::YukawaKernel{kappa}, panels);
  const Eigen::Index n = mesh.num_faces();
  const Eigen::MatrixXd sparse = Eigen::MatrixXd(y);
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
  CHECK(y.nonZeros() >= nonzero);
  // Written row by row into the counted room, left uncompressed (no second copy of the
  // storage): the room holds every entry, and each row's columns are strictly increasing
  // (Eigen's coefficient lookup searches them).
  CHECK(!y.isCompressed());
  CHECK(bem::stored_bytes(y) >= 12 * std::uint64_t(y.nonZeros()));
  Eigen::Index unsorted = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index previous = -1;
    for (bem::SparseRowMatrix::InnerIterator it(y, i); it; ++it) {
      unsorted += it.col() <= previous;
      previous = it.col();
    }
  }
  CHECK(unsorted == 0);
  CHECK(nonzero < n * n);  // the cutoff drops something on this plate

  // The row sizes the memory guard counts before assembly: two per panel with a nonzero
  // single-layer entry (every panel within the cutoff has one), at least the stored ones.
  const Eigen::VectorX<Eigen::Index> sizes =
      bem::yukawa_near_field_row_sizes(panels, tree, kappa, bem::YukawaAttenuation::negligible);
  REQUIRE(sizes.size() == n);
  Eigen::Index wrong = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index single = 0;
    for (Eigen::Index j = 0; j < n; ++j) single += sparse(i, n + j) != 0.0;
    wrong += sizes(i) != 2 * single;
    wrong += sizes(i) < y.row(i).nonZeros();
  }
  CHECK(wrong == 0);

  // The single-precision matrix of the H-matrix solver: the same slots, each value the
  // double one rounded once to float.
  const bem::SparseRowMatrixSingle y_single = bem::assemble_yukawa_near_field<float>(panels, tree, kappa);
  REQUIRE(y_single.nonZeros() == y.nonZeros());
  CHECK(bem::stored_bytes(y_single) == bem::stored_bytes(y) - 4 * std::uint64_t(y.data().allocatedSize()));
  Eigen::Index rounded_differently = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    bem::SparseRowMatrix::InnerIterator it(y, i);
    bem::SparseRowMatrixSingle::InnerIterator its(y_single, i);
    for (; it && its; ++it, ++its)
      rounded_differently += it.col() != its.col() || static_cast<float>(it.value()) != its.value();
    rounded_differently += bool(it) != bool(its);
  }
  CHECK(rounded_differently == 0);
}
