#include "bem/evaluate/laplace_treecode.hpp"

#include "bem/evaluate/near_panel_integrals.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "bem/evaluate/near_panel_integrals.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/quadrature/triangle_quadrature.hpp"
#include "core/errors.hpp"

namespace bemshape::bem {
namespace {

/// The cheapest rule on the triangle that integrates polynomials of degree `degree` exactly.
const TriangleRule& exact_rule(int degree) {
  if (degree <= 8)
    return symmetric_triangle_rule(std::max(degree, 1));
  return collapsed_gauss_rule((degree + 3) / 2);  // exact to 2n − 2 ≥ degree
}

/// m[k] = (−d)^β for the first `count` multi-indices of `table`.
void monomials(const MultiIndexTable& table, const Eigen::Vector3d& d, int count, double* m) {
  m[0] = 1.0;
  for (int k = 1; k < count; ++k)
    for (int i = 0; i < 3; ++i)
      if (const int l = table.lower(k, i); l >= 0) {
        m[k] = -d[i] * m[l];
        break;
      }
}

}  // namespace

LaplaceTreecodeParameters LaplaceTreecodeParameters::for_tolerance(double tolerance) {
  // The largest error measured with θ = 0.3 (docs/benchmarks.md, "Interior evaluation at
  // many points"): grids over the ball of 5120 faces and the hollow box of 7152 faces with
  // their H-matrix solutions (bench_fast_path interior … --sweep), grids of 10⁴ and 10⁵
  // nodes over the ball of 20,480 faces (p = 10 only; 5.4e−7 is one node of these), and the
  // points of tests/bem/evaluate/test_laplace_treecode.cpp. At equal error θ = 0.3 was
  // the cheapest of 0.3, 0.4 and 0.5 on the ball; the order sets the accuracy.
  struct Row {
    double error;
    LaplaceTreecodeParameters parameters;
  };
  static constexpr Row rows[] = {
      {5.3e-4, {4, 0.3}},  {1.9e-5, {6, 0.3}},  {1.1e-6, {8, 0.3}},
      {5.4e-7, {10, 0.3}}, {6.0e-9, {12, 0.3}}, {4.8e-10, {14, 0.3}},
  };
  for (const Row& row : rows)
    if (row.error <= tolerance)
      return row.parameters;
  return {LaplaceTreecodeParameters::kMaxOrder, 0.25};  // not measured: the most accurate
}

LaplaceTreecode::LaplaceTreecode(const std::vector<Panel>& panels, const ClusterTree& tree,
                                 const Eigen::Ref<const Eigen::MatrixX3d>& q,
                                 const Eigen::Ref<const Eigen::MatrixX3d>& phi,
                                 LaplaceTreecodeParameters parameters)
    : panels_(&panels),
      tree_(&tree),
      parameters_(parameters),
      table_(std::clamp(parameters.order, 0, LaplaceTreecodeParameters::kMaxOrder) + 1),
      coefficients_(MultiIndexTable::count(std::max(parameters.order, 0))) {
  const int p = parameters.order;
  if (p < 0 || p > LaplaceTreecodeParameters::kMaxOrder)
    throw InputError("treecode order " + std::to_string(p) + " is outside [0, " +
                     std::to_string(LaplaceTreecodeParameters::kMaxOrder) + "]");
  if (!(parameters.theta > 0.0 && parameters.theta < 1.0))
    throw InputError("treecode acceptance parameter theta = " + std::to_string(parameters.theta) +
                     " must lie in (0, 1)");
  const auto n = static_cast<Eigen::Index>(panels.size());
  if (q.rows() != n || phi.rows() != n || tree.root().size() != n)
    throw InternalError("LaplaceTreecode: panels, tree and densities differ in size");
  log_error_bound_ = (p + 1) * std::log(parameters.theta);

  raise_.resize(size_t(coefficients_));
  for (int k = 0; k < coefficients_; ++k)
    for (int i = 0; i < 3; ++i) {
      raise_[size_t(k)].index[size_t(i)] = table_.raise(k, i);
      raise_[size_t(k)].factor[size_t(i)] = table_.exponent(k)[size_t(i)] + 1;
    }

  const auto& perm = tree.permutation();
  q_.resize(n, 3);
  phi_.resize(n, 3);
  for (Eigen::Index t = 0; t < n; ++t) {
    q_.row(t) = q.row(perm[size_t(t)]);
    phi_.row(t) = phi.row(perm[size_t(t)]);
  }

  const auto& clusters = tree.clusters();
  const size_t nc = clusters.size();
  centre_.resize(nc);
  radius_.assign(nc, 0.0);
  for (size_t c = 0; c < nc; ++c) {
    const Cluster& cl = clusters[c];
    centre_[c] = 0.5 * (cl.box.lo + cl.box.hi);
    for (Eigen::Index t = cl.begin; t < cl.end; ++t)
      for (const auto& corner : panels[size_t(perm[size_t(t)])].corners)
        radius_[c] = std::max(radius_[c], (corner - centre_[c]).norm());
  }

  const int m = coefficients_;
  moments_.assign(nc * size_t(m) * kSets, 0.0);

  // Leaf moments from each panel's quadrature points (exact: the integrands are polynomials
  // of degree ≤ p on a flat panel).
  const TriangleRule& rule = exact_rule(p);
  const std::vector<int> leaves = tree.leaves();
  struct Lower {
    std::array<int, 3> index;
    std::array<double, 3> factor;
  };
  std::vector<Lower> lower(static_cast<size_t>(m));
  for (int b = 0; b < m; ++b)
    for (int j = 0; j < 3; ++j) {
      const int l = table_.lower(b, j);
      lower[size_t(b)].index[size_t(j)] = l < 0 ? m : l;
      lower[size_t(b)].factor[size_t(j)] = table_.exponent(b)[size_t(j)];
    }
#pragma omp parallel
  {
    std::vector<double> mono(size_t(m) + 1, 0.0);
#pragma omp for schedule(dynamic, 8)
    for (size_t l = 0; l < leaves.size(); ++l) {
      const size_t c = size_t(leaves[l]);
      const Cluster& cl = clusters[c];
      double* out = &moments_[c * size_t(m) * kSets];
      for (Eigen::Index t = cl.begin; t < cl.end; ++t) {
        const Panel& panel = panels[size_t(perm[size_t(t)])];
        for (int k = 0; k < rule.size(); ++k) {
          const auto qk = size_t(k);
          const Eigen::Vector3d y =
              panel.corners[0] + rule.xi[qk] * panel.edge1 + rule.eta[qk] * panel.edge2;
          monomials(table_, y - centre_[c], m, mono.data());
          const double w = panel.area * rule.weight[qk];
          // The monomials' zero slot (index m) stands for the missing (−d)^{β−e_j}.
          mono[size_t(m)] = 0.0;
          for (int b = 0; b < m; ++b) {
            // u = Σ_j n_j β_j (−d)^{β−e_j}: the dipole term.
            const Lower& low = lower[size_t(b)];
            const double u = panel.normal[0] * low.factor[0] * mono[size_t(low.index[0])] +
                             panel.normal[1] * low.factor[1] * mono[size_t(low.index[1])] +
                             panel.normal[2] * low.factor[2] * mono[size_t(low.index[2])];
            double* o = out + size_t(b) * kSets;
            for (int i = 0; i < 3; ++i)
              o[i] += w * (q_(t, i) * mono[size_t(b)] + phi_(t, i) * u);
            o[3] += w * u;
          }
        }
      }
    }
  }

  // Shift terms (β, γ, binom(β, γ)) of the moment translation, γ ≤ β componentwise.
  struct ShiftTerm {
    int beta, gamma, difference;
    double binomial;
  };
  std::vector<ShiftTerm> shift;
  const auto binom = [](int a, int b) {
    double r = 1.0;
    for (int k = 1; k <= b; ++k)
      r = r * (a - b + k) / k;
    return r;
  };
  for (int b = 0; b < m; ++b) {
    const auto& e = table_.exponent(b);
    for (int g1 = 0; g1 <= e[0]; ++g1)
      for (int g2 = 0; g2 <= e[1]; ++g2)
        for (int g3 = 0; g3 <= e[2]; ++g3)
          shift.push_back({b, table_.index(g1, g2, g3),
                           table_.index(e[0] - g1, e[1] - g2, e[2] - g3),
                           binom(e[0], g1) * binom(e[1], g2) * binom(e[2], g3)});
  }

  // Parents from their children, deepest level first (children follow their parents in the
  // breadth-first cluster order, so a level is a contiguous range).
  std::vector<int> depth(nc, 0);
  int max_depth = 0;
  for (size_t c = 0; c < nc; ++c)
    if (!clusters[c].is_leaf())
      for (int k = 0; k < 2; ++k) {
        depth[size_t(clusters[c].first_child + k)] = depth[c] + 1;
        max_depth = std::max(max_depth, depth[c] + 1);
      }
  for (int level = max_depth - 1; level >= 0; --level) {
#pragma omp parallel
    {
      std::vector<double> mono(size_t(m), 0.0);
#pragma omp for schedule(dynamic, 4)
      for (size_t c = 0; c < nc; ++c) {
        if (depth[c] != level || clusters[c].is_leaf())
          continue;
        double* out = &moments_[c * size_t(m) * kSets];
        for (int k = 0; k < 2; ++k) {
          const size_t child = size_t(clusters[c].first_child + k);
          monomials(table_, centre_[child] - centre_[c], m, mono.data());
          const double* in = &moments_[child * size_t(m) * kSets];
          for (const ShiftTerm& s : shift) {
            const double f = s.binomial * mono[size_t(s.difference)];
            for (int i = 0; i < kSets; ++i)
              out[size_t(s.beta) * kSets + size_t(i)] +=
                  f * in[size_t(s.gamma) * kSets + size_t(i)];
          }
        }
      }
    }
  }
}

LaplaceTreecode::Workspace LaplaceTreecode::workspace() const {
  Workspace w;
  w.taylor.resize(size_t(table_.size() + 1));
  w.stack.reserve(128);
  return w;
}

LaplaceTreecode::Value LaplaceTreecode::evaluate(const Eigen::Vector3d& x, Workspace& workspace,
                                                 TreecodeCounts& counts) const {
  return sum<true>(x, workspace, counts);
}

LaplaceTreecode::Value LaplaceTreecode::evaluate_values(const Eigen::Vector3d& x,
                                                        Workspace& workspace,
                                                        TreecodeCounts& counts) const {
  return sum<false>(x, workspace, counts);
}

template <bool kGradient>
LaplaceTreecode::Value LaplaceTreecode::sum(const Eigen::Vector3d& x, Workspace& workspace,
                                            TreecodeCounts& counts) const {
  const LaplaceKernel laplace{};
  const int p = parameters_.order;
  const double theta2 = parameters_.theta * parameters_.theta;
  const auto& perm = tree_->permutation();
  // pot[s], grad[s][k] for the 4 sets, 4π times the result.
  double pot[kSets] = {};
  double grad[kSets][3] = {};
  Value v;
  auto& stack = workspace.stack;
  double* b = workspace.taylor.data();
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const auto c = size_t(stack.back());
    stack.pop_back();
    const Cluster& cl = tree_->cluster(int(c));
    const Eigen::Vector3d R = x - centre_[c];
    const double r2 = R.squaredNorm();
    const double rho = radius_[c];
    if (rho * rho < theta2 * r2) {
      // Lowest order whose truncation bound (ρ/|R|)^{p'+1} is that of the worst accepted cluster.
      int order = p;
      if (rho > 0.0) {
        const double log_ratio = 0.5 * std::log(rho * rho / r2);  // < 0
        order = std::clamp(int(std::ceil(log_error_bound_ / log_ratio)) - 1, 0, p);
      } else {
        order = 0;
      }
      const int used = MultiIndexTable::count(order);
      inverse_distance_taylor(table_, R, kGradient ? order + 1 : order, b);
      const double* mom = &moments_[c * size_t(coefficients_) * kSets];
      if constexpr (!kGradient) {
        for (int k = 0; k < used; ++k) {
          const double* mk = mom + size_t(k) * kSets;
          for (int s = 0; s < kSets; ++s) pot[s] += mk[s] * b[k];
        }
        ++counts.expansions;
        continue;
      }
      for (int k = 0; k < used; ++k) {
        const double* mk = mom + size_t(k) * kSets;
        const Raise& up = raise_[size_t(k)];
        const double bk = b[k];
        const double g0 = up.factor[0] * b[up.index[0]];
        const double g1 = up.factor[1] * b[up.index[1]];
        const double g2 = up.factor[2] * b[up.index[2]];
        for (int s = 0; s < kSets; ++s) {
          pot[s] += mk[s] * bk;
          grad[s][0] += mk[s] * g0;
          grad[s][1] += mk[s] * g1;
          grad[s][2] += mk[s] * g2;
        }
      }
      ++counts.expansions;
    } else if (cl.is_leaf()) {
      for (Eigen::Index t = cl.begin; t < cl.end; ++t) {
        const Panel& panel = (*panels_)[size_t(perm[size_t(t)])];
        const PanelIntegrals l = parameters_.near_field_at_treecode_accuracy
                                     ? near_panel_integrals(panel, x, kGradient)
                                     : integrate_panel(laplace, panel, x, kGradient);
        v.winding -= l.double_layer;
        const Eigen::RowVector3d q = q_.row(t), phi = phi_.row(t);
        v.s += l.single_layer * q - l.double_layer * phi;
        if constexpr (kGradient)
          v.gradient += q.transpose() * l.single_layer_gradient.transpose() -
                      phi.transpose() * l.double_layer_gradient.transpose();
      }
      counts.panel_integrals += std::uint64_t(cl.size());
    } else {
      stack.push_back(cl.first_child + 1);
      stack.push_back(cl.first_child);
    }
  }
  constexpr double f = LaplaceKernel::inv_four_pi;
  for (int i = 0; i < 3; ++i) {
    v.s(i) += f * pot[i];
    for (int j = 0; j < 3; ++j)
      v.gradient(i, j) += f * grad[i][j];
  }
  v.winding += f * pot[3];
  return v;
}

}  // namespace bemshape::bem
