#include "bem/hierarchical/gmres.hpp"

#include <cmath>

#include <Eigen/Dense>

namespace bemshape::bem {
namespace {

/// An Arnoldi vector shorter than this fraction of A·z before orthogonalisation is a
/// breakdown: A·z lies in the Krylov space already (to rounding).
constexpr double kBreakdown = 1e-14;

}  // namespace

GmresResult gmres(const LinearOperator& a, const LinearOperator& preconditioner,
                  const Eigen::VectorXd& b, Eigen::VectorXd& x, const GmresOptions& options,
                  const std::function<void(int, double)>& monitor) {
  const Eigen::Index n = b.size();
  const int m = std::max(1, options.restart);
  GmresResult result;
  const double norm_b = b.norm();
  if (x.size() != n) x = Eigen::VectorXd::Zero(n);
  if (norm_b == 0.0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  const auto apply_preconditioner = [&](const Eigen::VectorXd& v, Eigen::VectorXd& z) {
    if (preconditioner)
      preconditioner(v, z);
    else
      z = v;
  };
  Eigen::VectorXd r(n), w(n), z(n);
  a(x, w);
  r = b - w;
  double beta = r.norm();
  Eigen::MatrixXd basis(n, m + 1);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(m + 1, m);
  Eigen::VectorXd cs(m), sn(m), g(m + 1);
  while (beta > options.tolerance * norm_b && result.iterations < options.max_iterations) {
    basis.col(0) = r / beta;
    g.setZero();
    g(0) = beta;
    h.setZero();
    int k = 0;
    for (; k < m && result.iterations < options.max_iterations; ++k) {
      apply_preconditioner(basis.col(k), z);
      a(z, w);
      ++result.iterations;
      const double w_before = w.norm();
      for (int i = 0; i <= k; ++i) {
        h(i, k) = w.dot(basis.col(i));
        w -= h(i, k) * basis.col(i);
      }
      const double w_norm = w.norm();
      h(k + 1, k) = w_norm;
      for (int i = 0; i < k; ++i) {  // previous rotations
        const double t = cs(i) * h(i, k) + sn(i) * h(i + 1, k);
        h(i + 1, k) = -sn(i) * h(i, k) + cs(i) * h(i + 1, k);
        h(i, k) = t;
      }
      const double rho = std::sqrt(h(k, k) * h(k, k) + h(k + 1, k) * h(k + 1, k));
      if (!(rho > kBreakdown * w_before)) break;  // A·z_k adds nothing: keep the first k steps
      cs(k) = h(k, k) / rho;
      sn(k) = h(k + 1, k) / rho;
      h(k, k) = rho;
      h(k + 1, k) = 0.0;
      g(k + 1) = -sn(k) * g(k);
      g(k) = cs(k) * g(k);
      const double estimate = std::abs(g(k + 1)) / norm_b;
      if (monitor) monitor(result.iterations, estimate);
      if (estimate <= options.tolerance || !(w_norm > kBreakdown * w_before)) {
        ++k;  // converged, or the Krylov space is invariant (the residual cannot shrink more)
        break;
      }
      basis.col(k + 1) = w / w_norm;
    }
    // x += M⁻¹ V_k y with H_k y = g_k (upper triangular after the rotations).
    if (k == 0) break;  // no usable direction
    const Eigen::VectorXd y =
        h.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    apply_preconditioner(basis.leftCols(k) * y, z);
    x += z;
    a(x, w);
    r = b - w;
    const double new_beta = r.norm();
    if (!(new_beta < beta)) {  // stagnation (or NaN): restarting would not help
      beta = new_beta;
      break;
    }
    beta = new_beta;
  }
  result.residual = beta / norm_b;
  result.converged = result.residual <= options.tolerance;
  return result;
}

}  // namespace bemshape::bem
