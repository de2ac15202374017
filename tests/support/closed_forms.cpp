#include "tests/support/closed_forms.hpp"

#include <cmath>

#include <Eigen/Dense>

namespace bemshape::testing {
namespace {

// Modified spherical Bessel functions of order 1 (unnormalised):
//   k1(z) = e^{−z}(1+z)/z²        decays, k1'(z)/k1(z) = −1 + 1/(1+z) − 2/z
//   i1(z) = (z cosh z − sinh z)/z²  regular at 0, i1'(z) = sinh(z)/z − 2 i1(z)/z
double k1(double z) { return std::exp(-z) * (1.0 + z) / (z * z); }
double dk1(double z) { return k1(z) * (-1.0 + 1.0 / (1.0 + z) - 2.0 / z); }
double i1(double z) {
  if (z < 1e-3) return z / 3.0;  // series z/3 + z³/30: the closed form cancels badly here
  return (z * std::cosh(z) - std::sinh(z)) / (z * z);
}
double di1(double z) {
  if (z < 1e-3) return 1.0 / 3.0;
  return std::sinh(z) / z - 2.0 * i1(z) / z;
}

Eigen::Vector3d radial_field(double psi, const Eigen::Vector3d& x) {
  const double r = x.norm();
  return r > 0.0 ? Eigen::Vector3d(psi * x / r) : Eigen::Vector3d::Zero();
}

}  // namespace

BallSolution ball_solution(const PdeParameters& p, double radius) {
  BallSolution sol;
  sol.radius = radius;
  sol.kappa = p.kappa();
  const double z = sol.kappa * radius;
  sol.A = 1.0 / (p.a_tilde() * (2.0 + z + 1.0 / (1.0 + z)));
  sol.D = sol.A * radius / k1(z);
  return sol;
}

double BallSolution::psi(double r) const {
  return r <= radius ? A * r : D * k1(kappa * r);
}

Eigen::Vector3d BallSolution::s(const Eigen::Vector3d& x) const {
  return radial_field(psi(x.norm()), x);
}

ShellSolution shell_solution(const PdeParameters& p, double inner_radius, double outer_radius) {
  ShellSolution sol;
  sol.inner_radius = inner_radius;
  sol.outer_radius = outer_radius;
  sol.kappa = p.kappa();
  const double k = sol.kappa, r1 = inner_radius, r2 = outer_radius, jump = 1.0 / p.a_tilde();
  // Unknowns (A, B, C̃, D̃) with C̃ = C·i1(κR1) and D̃ = D·k1(κR2), the values of ψ on the
  // two spheres from the cavity and exterior sides, so the columns are of comparable size
  // (k1 and i1 themselves span thirty orders of magnitude here). On both spheres ψ is
  // continuous and ψ'_solid − ψ'_other = 1/ã (on the inner sphere n = −x̂ and n_i = −x_i/r,
  // so the sign works out the same).
  Eigen::Matrix4d m;
  Eigen::Vector4d rhs;
  m << r2, 1.0 / (r2 * r2), 0.0, -1.0,                                        //
      1.0, -2.0 / (r2 * r2 * r2), 0.0, -k * dk1(k * r2) / k1(k * r2),         //
      r1, 1.0 / (r1 * r1), -1.0, 0.0,                                         //
      1.0, -2.0 / (r1 * r1 * r1), -k * di1(k * r1) / i1(k * r1), 0.0;
  rhs << 0.0, jump, 0.0, jump;
  const Eigen::Vector4d c = m.partialPivLu().solve(rhs);
  sol.A = c(0);
  sol.B = c(1);
  sol.C = c(2) / i1(k * r1);
  sol.D = c(3) / k1(k * r2);
  return sol;
}

double ShellSolution::psi(double r) const {
  if (r < inner_radius) return C * i1(kappa * r);
  if (r <= outer_radius) return A * r + B / (r * r);
  return D * k1(kappa * r);
}

Eigen::Vector3d ShellSolution::s(const Eigen::Vector3d& x) const {
  return radial_field(psi(x.norm()), x);
}

TubeSolution tube_solution(const PdeParameters& p, double inner_radius, double outer_radius) {
  TubeSolution sol;
  sol.inner_radius = inner_radius;
  sol.outer_radius = outer_radius;
  sol.kappa = p.kappa();
  const double k = sol.kappa, r1 = inner_radius, r2 = outer_radius, jump = 1.0 / p.a_tilde();
  // As for the shell: unknowns (A, B, C̃, D̃) with C̃ = C·I1(κR1), D̃ = D·K1(κR2), ψ
  // continuous and ψ'_solid − ψ'_other = 1/ã on both cylinders.
  const double i1 = std::cyl_bessel_i(1.0, k * r1), k1 = std::cyl_bessel_k(1.0, k * r2);
  // I1' = I0 − I1/z, K1' = −K0 − K1/z.
  const double di1 = std::cyl_bessel_i(0.0, k * r1) - i1 / (k * r1);
  const double dk1 = -std::cyl_bessel_k(0.0, k * r2) - k1 / (k * r2);
  Eigen::Matrix4d m;
  Eigen::Vector4d rhs;
  m << r2, 1.0 / r2, 0.0, -1.0,                          //
      1.0, -1.0 / (r2 * r2), 0.0, -k * dk1 / k1,         //
      r1, 1.0 / r1, -1.0, 0.0,                           //
      1.0, -1.0 / (r1 * r1), -k * di1 / i1, 0.0;
  rhs << 0.0, jump, 0.0, jump;
  const Eigen::Vector4d c = m.partialPivLu().solve(rhs);
  sol.A = c(0);
  sol.B = c(1);
  sol.C = c(2) / i1;
  sol.D = c(3) / k1;
  return sol;
}

double TubeSolution::psi(double rho) const {
  if (rho < inner_radius) return C * std::cyl_bessel_i(1.0, kappa * rho);
  if (rho <= outer_radius) return A * rho + B / rho;
  return D * std::cyl_bessel_k(1.0, kappa * rho);
}

double TubeSolution::mid_radius() const { return std::sqrt(-B / A); }

double plate_slope(const PdeParameters& p, double thickness) {
  return 2.0 / (p.a_tilde() * (p.kappa() * thickness + 2.0));
}

double rod_slope(const PdeParameters& p, double radius) {
  const double z = p.kappa() * radius;
  return 1.0 / (p.a_tilde() * (2.0 + z * std::cyl_bessel_k(0.0, z) / std::cyl_bessel_k(1.0, z)));
}

Interval1DSolution interval_1d_solution(const PdeParameters& p, double K, double L, double pos,
                                        double h) {
  Interval1DSolution sol;
  const double lam = std::sqrt(p.alpha() / p.a_tilde());
  const double at = p.a_tilde();
  sol.lambda = lam;
  sol.pos = pos;
  sol.h = h;
  auto e = [](double t) { return std::exp(t); };
  const double den = (2.0 + lam * h) * e(2.0 * lam * (L + pos)) +
                     (lam * h * e(2.0 * lam * L) + (2.0 - lam * h) * e(2.0 * lam * (pos + h))) *
                         e(2.0 * lam * K) +
                     lam * h * e(2.0 * lam * (2.0 * pos + h));
  // The constants as printed in the paper, except two misprints that vanish in the limit
  // K → −∞, L → ∞: c2 needs a minus sign between its exponentials (s(K) = 0 forces
  // c2 = −c1·e^{2λK}), and the second exponential of c5 is e^{λ(3p+h)}, not e^{λ(2p+h)}
  // (s(L) = 0 forces c5 = −c6·e^{−2λL}). docs/theory.md records both.
  sol.c1 = -(h / at) * (e(lam * (2.0 * L + pos)) - e(lam * (3.0 * pos + 2.0 * h))) / den;
  sol.c2 = (h * e(2.0 * lam * K) / at) * (e(lam * (2.0 * L + pos)) - e(lam * (3.0 * pos + 2.0 * h))) / den;
  sol.c3 = -(2.0 / at) * (e(2.0 * lam * (K + pos + h)) - e(2.0 * lam * (L + pos))) / den;
  sol.c4 = (1.0 / at) *
           (-(2.0 * pos + h) * e(2.0 * lam * (L + pos)) +
            (h * e(2.0 * lam * L) + (2.0 * pos + h) * e(2.0 * lam * (pos + h))) * e(2.0 * lam * K) -
            h * e(2.0 * lam * (2.0 * pos + h))) /
           den;
  sol.c5 = -(h / at) * (e(lam * (2.0 * K + pos + h)) + e(lam * (3.0 * pos + h))) / den;
  sol.c6 = (h / at) * (e(lam * (2.0 * L + 2.0 * K + pos + h)) + e(lam * (2.0 * L + 3.0 * pos + h))) / den;
  return sol;
}

double Interval1DSolution::s(double x) const {
  if (x < pos) return c1 * std::exp(lambda * x) + c2 * std::exp(-lambda * x);
  if (x <= pos + h) return c3 * x + c4;
  return c5 * std::exp(lambda * x) + c6 * std::exp(-lambda * x);
}

}  // namespace bemshape::testing
