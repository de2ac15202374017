// Q1 element integrals against their defining properties: partition of unity (mass entries
// sum to the cell volume, stiffness rows sum to zero), the divergence theorem for the
// gradient integrals, and the exact Laplacian stencils of bilinear/trilinear elements.
#include <catch2/catch.hpp>

#include "fem/q1_element.hpp"

using namespace bemshape::fem;

namespace {

template <int D>
std::array<int, D> offset(int a, int b) {
  const auto qa = corner_of<D>(a), qb = corner_of<D>(b);
  std::array<int, D> o{};
  for (int d = 0; d < D; ++d)
    o[d] = qb[d] - qa[d];
  return o;
}

template <int D>
void check_partition_of_unity(double h) {
  double mass = 0.0;
  for (int a = 0; a < (1 << D); ++a) {
    double row = 0.0;
    for (int b = 0; b < (1 << D); ++b) {
      mass += q1_mass<D>(offset<D>(a, b), h);
      row += q1_stiffness<D>(offset<D>(a, b), h);
    }
    CHECK(row == Approx(0.0).margin(1e-12 / h));
  }
  CHECK(mass == Approx(std::pow(h, D)).epsilon(1e-14));
}

}  // namespace

TEST_CASE("Q1 mass sums to the cell volume, stiffness rows to zero") {
  check_partition_of_unity<2>(0.3);
  check_partition_of_unity<3>(0.07);
}

TEST_CASE("Q1 element stiffness is the classical bilinear stencil") {
  // Bilinear element on a square: diagonal 2/3, edge neighbour −1/6, opposite corner −1/3,
  // independent of h in 2-D.
  CHECK(q1_stiffness<2>({0, 0}, 0.5) == Approx(2.0 / 3.0));
  CHECK(q1_stiffness<2>({1, 0}, 0.5) == Approx(-1.0 / 6.0));
  CHECK(q1_stiffness<2>({1, 1}, 0.5) == Approx(-1.0 / 3.0));
  // Trilinear: diagonal h/3, face-diagonal −h/12, space-diagonal −h/12, edge 0.
  const double h = 0.2;
  CHECK(q1_stiffness<3>({0, 0, 0}, h) == Approx(h / 3.0));
  CHECK(q1_stiffness<3>({1, 0, 0}, h) == Approx(0.0).margin(1e-15));
  CHECK(q1_stiffness<3>({1, 1, 0}, h) == Approx(-h / 12.0));
  CHECK(q1_stiffness<3>({1, 1, 1}, h) == Approx(-h / 12.0));
}

TEST_CASE("Q1 gradient integrals obey the divergence theorem") {
  // ∫_cell ∂φ_q/∂x_i summed over q is ∫ ∂1/∂x_i = 0; over the corners with q_i = 1 it is the
  // area of the face x_i = h.
  const double h = 0.4;
  for (int i = 0; i < 3; ++i) {
    double total = 0.0, upper = 0.0;
    for (int q = 0; q < 8; ++q) {
      const double g = q1_gradient_integral<3>(corner_of<3>(q), i, h);
      total += g;
      if (corner_of<3>(q)[i] == 1)
        upper += g;
    }
    CHECK(total == Approx(0.0).margin(1e-15));
    CHECK(upper == Approx(h * h));
  }
}

TEST_CASE("Q1 centre gradient is exact for trilinear functions") {
  // u = 1 + 2x − 3y + 0.5z + xy: the centre gradient of the interpolant is (2 + y_c, −3 + x_c,
  // 0.5).
  const double h = 0.25;
  std::array<double, 3> grad{};
  for (int q = 0; q < 8; ++q) {
    const auto c = corner_of<3>(q);
    const double x = c[0] * h, y = c[1] * h, z = c[2] * h;
    const double u = 1 + 2 * x - 3 * y + 0.5 * z + x * y;
    for (int i = 0; i < 3; ++i)
      grad[i] += q1_centre_gradient_weight<3>(c, i, h) * u;
  }
  CHECK(grad[0] == Approx(2.0 + 0.5 * h));
  CHECK(grad[1] == Approx(-3.0 + 0.5 * h));
  CHECK(grad[2] == Approx(0.5));
}
