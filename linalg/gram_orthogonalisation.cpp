#include "linalg/gram_orthogonalisation.hpp"

#include <algorithm>
#include <limits>

#include <Eigen/Eigenvalues>

namespace bemshape::linalg {

double resolved_eigenvalues(double epsilon) {
  constexpr double u = 0.5 * std::numeric_limits<double>::epsilon();
  return std::min(0.5, 100.0 * u * u / (epsilon * epsilon));
}

void orthogonalise_columns(Eigen::Ref<Eigen::MatrixXd> c, Eigen::Ref<Eigen::MatrixXd> w,
                           double negligible2, double resolved) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(c.transpose() * c);
  const Eigen::MatrixXd& x = gram.eigenvectors();  // columns by ascending eigenvalue
  const Eigen::MatrixXd rotated_c = c * x, rotated_w = w * x;
  c = rotated_c;
  w = rotated_w;
  const Eigen::VectorXd& lambda = gram.eigenvalues();
  const double largest = lambda(lambda.size() - 1);
  Eigen::Index small = 0;
  while (small < lambda.size() && lambda(small) < resolved * largest)
    ++small;
  if (small < 2 || small == lambda.size())
    return;
  if (c.leftCols(small).squaredNorm() <= negligible2)
    return;
  orthogonalise_columns(c.leftCols(small), w.leftCols(small), negligible2, resolved);
}

}  // namespace bemshape::linalg
