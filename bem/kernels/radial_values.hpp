#pragma once
// A radial kernel G(r) and its derivative G'(r) at one distance r, as the kernels
// (bem/kernels/laplace_kernel.hpp, bem/kernels/yukawa_kernel.hpp) return them together: the quadrature loops
// need both at every point, and the Yukawa kernel then computes its exponential once.

namespace bemshape::bem {

struct RadialValues {
  double value;              ///< G(r) [1/model units]
  double radial_derivative;  ///< G'(r) [1/model units²]
};

}  // namespace bemshape::bem
