#pragma once
// All shape features at a set of points, from the solution s and its gradient there.
// Shared by the boundary element path (surface and interior evaluation) and the voxel
// finite-element path, so both report exactly the same functions.
//
//   s:       #P×d values of s [model units]
//   grad_s:  #P×(d·d) gradients, row p holding ∂s_i/∂x_j at index i·d + j [dimensionless]
//   inside:  #P flags, χ at each point (1 inside the solid, 0 outside)
//
// Outside the solid (χ = 0) f_h, h_f, h_p and the skeleton are 0, as in the paper (they
// carry the factor χ); n_f is still s/|s|. Every output is finite (see thickness.hpp,
// orientation.hpp and skeleton.hpp for the degenerate cases).

#include <vector>

#include <Eigen/Core>

#include "features/feature_parameters.hpp"

namespace bemshape::features {

template <int D>
struct FeatureField {
  Eigen::VectorXd f_h;          ///< #P inverse thickness h0²·div s [dimensionless]
  Eigen::VectorXd h_f;          ///< #P paper thickness [model units]
  Eigen::VectorXd h_p;          ///< #P principal thickness [model units]
  Eigen::MatrixXd eigenvalues;  ///< #P×d feature-tensor eigenvalues, ascending [1]
  Eigen::MatrixXd n_f;          ///< #P×d normal orientation s/|s|
  Eigen::MatrixXd t_f;          ///< #P×d tangential orientation (3-D: eigenvector of λ1)
  Eigen::MatrixXd across;       ///< #P×d eigenvector of λd (direction across the wall)
  std::vector<char> skeleton;   ///< #P skeleton flags f_s (0 or 1)
};

/// Evaluates every feature function at #P points.
template <int D>
FeatureField<D> compute_features(const Eigen::Ref<const Eigen::MatrixXd>& s,
                                 const Eigen::Ref<const Eigen::MatrixXd>& grad_s,
                                 const std::vector<char>& inside,
                                 const FeatureParameters& parameters);

extern template FeatureField<2> compute_features<2>(const Eigen::Ref<const Eigen::MatrixXd>&,
                                                    const Eigen::Ref<const Eigen::MatrixXd>&,
                                                    const std::vector<char>&,
                                                    const FeatureParameters&);
extern template FeatureField<3> compute_features<3>(const Eigen::Ref<const Eigen::MatrixXd>&,
                                                    const Eigen::Ref<const Eigen::MatrixXd>&,
                                                    const std::vector<char>&,
                                                    const FeatureParameters&);

}  // namespace bemshape::features
