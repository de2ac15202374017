#include "bem/evaluate/inverse_distance_taylor.hpp"

#include <cmath>

#include "core/errors.hpp"

namespace bemshape::bem {

MultiIndexTable::MultiIndexTable(int degree) : degree_(degree) {
  if (degree < 0)
    throw InternalError("MultiIndexTable: degree must be non-negative");
  for (int n = 0; n <= degree; ++n)
    for (int b1 = n; b1 >= 0; --b1)
      for (int b2 = n - b1; b2 >= 0; --b2)
        exponents_.push_back({b1, b2, n - b1 - b2});
  const size_t m = exponents_.size();
  lower_.resize(m);
  lower2_.resize(m);
  raise_.resize(m);
  for (size_t k = 0; k < m; ++k) {
    const auto& e = exponents_[k];
    for (int i = 0; i < 3; ++i) {
      std::array<int, 3> down = e, down2 = e, up = e;
      --down[size_t(i)];
      down2[size_t(i)] -= 2;
      ++up[size_t(i)];
      lower_[k][size_t(i)] = down[size_t(i)] < 0 ? -1 : index(down[0], down[1], down[2]);
      lower2_[k][size_t(i)] = down2[size_t(i)] < 0 ? -1 : index(down2[0], down2[1], down2[2]);
      raise_[k][size_t(i)] = index(up[0], up[1], up[2]);
    }
  }
  const int zero = size();
  recurrence_.resize(m);
  for (size_t k = 1; k < m; ++k) {
    const auto& e = exponents_[k];
    const double n = e[0] + e[1] + e[2];
    RecurrenceStep& step = recurrence_[k];
    for (size_t i = 0; i < 3; ++i) {
      step.lower[i] = lower_[k][i] < 0 ? zero : lower_[k][i];
      step.lower2[i] = lower2_[k][i] < 0 ? zero : lower2_[k][i];
    }
    step.first = (2 * n - 1) / n;
    step.second = (n - 1) / n;
  }
}

int MultiIndexTable::index(int b1, int b2, int b3) const {
  const int n = b1 + b2 + b3;
  if (b1 < 0 || b2 < 0 || b3 < 0 || n > degree_)
    return -1;
  // Entries of degree n start at count(n − 1); within the degree, b1 descending, then b2
  // descending: (n − b1) earlier values of b1 hold 1, 2, …, n − b1 entries.
  const int before_b1 = (n - b1) * (n - b1 + 1) / 2;
  return (n == 0 ? 0 : count(n - 1)) + before_b1 + (n - b1 - b2);
}

void inverse_distance_taylor(const MultiIndexTable& table, const Eigen::Vector3d& R, int degree,
                             double* b) {
  const double r2 = R.squaredNorm();
  const double inv_r2 = 1.0 / r2;
  b[0] = std::sqrt(inv_r2);
  b[table.size()] = 0.0;
  const int end = MultiIndexTable::count(degree);
  const MultiIndexTable::RecurrenceStep* steps = table.recurrence().data();
  const double x = -R[0] * inv_r2, y = -R[1] * inv_r2, z = -R[2] * inv_r2;
  for (int k = 1; k < end; ++k) {
    const auto& s = steps[k];
    const double first = x * b[s.lower[0]] + y * b[s.lower[1]] + z * b[s.lower[2]];
    const double second = b[s.lower2[0]] + b[s.lower2[1]] + b[s.lower2[2]];
    b[k] = s.first * first - s.second * inv_r2 * second;
  }
}

}  // namespace bemshape::bem
