#include "features/point_features.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "features/feature_tensor.hpp"
#include "features/orientation.hpp"
#include "features/skeleton.hpp"
#include "features/thickness.hpp"

namespace bemshape::features {

void validate(const FeatureParameters& p) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(p.h0))
    throw InputError("h0 must be a positive length (got " + std::to_string(p.h0) +
                     "); choose about the smallest wall thickness of interest");
  if (!positive(p.a))
    throw InputError("a must be a positive number (got " + std::to_string(p.a) +
                     "); the paper's default is 0.2");
  if (!std::isfinite(p.skeleton_width) || p.skeleton_width < 0.0)
    throw InputError("the skeleton width w must be a non-negative length");
}

template <int D>
FeatureField<D> compute_features(const Eigen::Ref<const Eigen::MatrixXd>& s,
                                 const Eigen::Ref<const Eigen::MatrixXd>& grad_s,
                                 const std::vector<char>& inside,
                                 const FeatureParameters& parameters) {
  validate(parameters);
  const Eigen::Index n = s.rows();
  if (s.cols() != D || grad_s.cols() != D * D || grad_s.rows() != n ||
      static_cast<Eigen::Index>(inside.size()) != n) {
    std::ostringstream msg;
    msg << "compute_features<" << D << ">: expected s #P×" << D << ", grad_s #P×" << D * D
        << " and #P inside flags; got " << s.rows() << "×" << s.cols() << ", " << grad_s.rows()
        << "×" << grad_s.cols() << " and " << inside.size();
    throw InternalError(msg.str());
  }
  const double h0 = parameters.h0, a = parameters.a;
  FeatureField<D> out;
  out.f_h = Eigen::VectorXd::Zero(n);
  out.h_f = Eigen::VectorXd::Zero(n);
  out.h_p = Eigen::VectorXd::Zero(n);
  out.eigenvalues = Eigen::MatrixXd::Zero(n, D);
  out.n_f = Eigen::MatrixXd::Zero(n, D);
  out.t_f = Eigen::MatrixXd::Zero(n, D);
  out.across = Eigen::MatrixXd::Zero(n, D);
  out.skeleton.assign(static_cast<size_t>(n), 0);
  for (Eigen::Index p = 0; p < n; ++p) {
    const Eigen::Matrix<double, D, 1> sp = s.row(p).transpose();
    Eigen::Matrix<double, D, D> g;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) g(i, j) = grad_s(p, i * D + j);
    if (!sp.allFinite() || !g.allFinite()) {
      std::ostringstream msg;
      msg << "shape features: the solution is not finite at point " << p
          << " (the solver produced NaN or Inf)";
      throw NumericalError(msg.str());
    }
    const FeatureTensor<D> tensor = feature_tensor<D>(g);
    const Eigen::Matrix<double, D, 1> n_f = normal_orientation<D>(sp, h0);
    out.n_f.row(p) = n_f.transpose();
    out.eigenvalues.row(p) = tensor.eigenvalues.transpose();
    out.across.row(p) = tensor.eigenvectors.col(D - 1).transpose();
    if constexpr (D == 2) {
      out.t_f.row(p) = tangential_orientation(Eigen::Vector2d(n_f)).transpose();
    } else {
      out.t_f.row(p) = tensor.eigenvectors.col(0).transpose();
    }
    if (!inside[static_cast<size_t>(p)]) continue;
    const double f_h = inverse_thickness(g.trace(), h0);
    out.f_h(p) = f_h;
    out.h_f(p) = paper_thickness(f_h, h0, a);
    out.h_p(p) = principal_thickness(tensor.eigenvalues(D - 1), h0, a);
    out.skeleton[static_cast<size_t>(p)] = on_skeleton<D>(sp, tensor, parameters.skeleton_width);
  }
  return out;
}

template FeatureField<2> compute_features<2>(const Eigen::Ref<const Eigen::MatrixXd>&,
                                             const Eigen::Ref<const Eigen::MatrixXd>&,
                                             const std::vector<char>&, const FeatureParameters&);
template FeatureField<3> compute_features<3>(const Eigen::Ref<const Eigen::MatrixXd>&,
                                             const Eigen::Ref<const Eigen::MatrixXd>&,
                                             const std::vector<char>&, const FeatureParameters&);

}  // namespace bemshape::features
