#include "bem/hierarchical/gmres.hpp"

#include <cmath>

#include <Eigen/Dense>

namespace bemshape::bem {
namespace {

/// An Arnoldi vector shorter than this fraction of A·z before orthogonalisation is a
/// breakdown: A·z lies in the Krylov space already (to rounding).
constexpr double kBreakdown = 1e-14;

/// One column's restarted GMRES, advanced one operator application at a time by the
/// driver below. Each application is of one of three kinds:
///   residual — w = A x, then r = b − w starts a cycle (or ends the solve);
///   arnoldi  — w = A M⁻¹ v_k, one Arnoldi step of the cycle;
///   update   — x += M⁻¹ V_k y_k (the cycle's correction), then w = A x as for residual.
class ColumnGmres {
 public:
  enum class Step { residual, arnoldi, update, done };

  ColumnGmres(Eigen::VectorXd b, Eigen::VectorXd x, const GmresOptions& options)
      : b_(std::move(b)), x_(std::move(x)), options_(options), m_(std::max(1, options.restart)) {
    norm_b_ = b_.norm();
    if (norm_b_ == 0.0) {
      x_.setZero();
      result_.converged = true;
      step_ = Step::done;
    } else if (x_.isZero(0.0)) {
      take_residual(Eigen::VectorXd::Zero(b_.size()));  // A·0 = 0: no product needed
    }
  }

  Step step() const { return step_; }
  bool wants_preconditioner() const { return step_ == Step::arnoldi || step_ == Step::update; }

  /// The vector M⁻¹ is to be applied to in this step (arnoldi, update).
  Eigen::VectorXd preconditioner_input() const {
    if (step_ == Step::arnoldi) return basis_.col(k_);
    // H_k y = g_k (upper triangular after the rotations).
    const Eigen::VectorXd y =
        h_.topLeftCorner(k_, k_).triangularView<Eigen::Upper>().solve(g_.head(k_));
    return basis_.leftCols(k_) * y;
  }

  /// The vector A is to be applied to, given M⁻¹ of preconditioner_input() when wanted.
  Eigen::VectorXd operand(const Eigen::Ref<const Eigen::VectorXd>& z) {
    if (step_ == Step::arnoldi) return z;
    if (step_ == Step::update) {
      x_ += z;
      after_update_ = true;
    }
    return x_;
  }

  /// Takes w = A·operand() and moves to the next step.
  void take(const Eigen::Ref<const Eigen::VectorXd>& w,
            const std::function<void(int, int, double)>& monitor, int column) {
    if (step_ == Step::arnoldi)
      take_arnoldi(w, monitor, column);
    else
      take_residual(w);
  }

  const Eigen::VectorXd& solution() const { return x_; }
  const GmresResult& result() const { return result_; }

 private:
  void take_residual(const Eigen::Ref<const Eigen::VectorXd>& w) {
    const Eigen::VectorXd r = b_ - w;
    const double new_beta = r.norm();
    if (after_update_ && !(new_beta < beta_)) {  // stagnation (or NaN): a restart won't help
      beta_ = new_beta;
      finish();
      return;
    }
    beta_ = new_beta;
    if (!(beta_ > options_.tolerance * norm_b_) ||
        result_.iterations >= options_.max_iterations) {
      finish();
      return;
    }
    if (basis_.size() == 0) {
      basis_.resize(b_.size(), m_ + 1);
      h_.resize(m_ + 1, m_);
      cs_.resize(m_);
      sn_.resize(m_);
      g_.resize(m_ + 1);
    }
    basis_.col(0) = r / beta_;
    g_.setZero();
    g_(0) = beta_;
    h_.setZero();
    k_ = 0;
    step_ = Step::arnoldi;
  }

  void take_arnoldi(const Eigen::Ref<const Eigen::VectorXd>& product,
                    const std::function<void(int, int, double)>& monitor, int column) {
    Eigen::VectorXd w = product;
    ++result_.iterations;
    const int k = k_;
    const double w_before = w.norm();
    for (int i = 0; i <= k; ++i) {  // modified Gram–Schmidt
      h_(i, k) = w.dot(basis_.col(i));
      w -= h_(i, k) * basis_.col(i);
    }
    const double w_norm = w.norm();
    h_(k + 1, k) = w_norm;
    for (int i = 0; i < k; ++i) {  // previous rotations
      const double t = cs_(i) * h_(i, k) + sn_(i) * h_(i + 1, k);
      h_(i + 1, k) = -sn_(i) * h_(i, k) + cs_(i) * h_(i + 1, k);
      h_(i, k) = t;
    }
    const double rho = std::sqrt(h_(k, k) * h_(k, k) + h_(k + 1, k) * h_(k + 1, k));
    if (!(rho > kBreakdown * w_before)) {  // A·z_k adds nothing: keep the first k steps
      end_cycle();
      return;
    }
    cs_(k) = h_(k, k) / rho;
    sn_(k) = h_(k + 1, k) / rho;
    h_(k, k) = rho;
    h_(k + 1, k) = 0.0;
    g_(k + 1) = -sn_(k) * g_(k);
    g_(k) = cs_(k) * g_(k);
    const double estimate = std::abs(g_(k + 1)) / norm_b_;
    if (monitor) monitor(column, result_.iterations, estimate);
    ++k_;
    if (estimate <= options_.tolerance || !(w_norm > kBreakdown * w_before)) {
      end_cycle();  // converged, or the Krylov space is invariant (the residual cannot shrink)
      return;
    }
    basis_.col(k_) = w / w_norm;
    if (k_ < m_ && result_.iterations < options_.max_iterations)
      step_ = Step::arnoldi;
    else
      end_cycle();
  }

  void end_cycle() {
    if (k_ == 0)
      finish();  // no usable direction
    else
      step_ = Step::update;
  }

  void finish() {
    result_.residual = beta_ / norm_b_;
    result_.converged = result_.residual <= options_.tolerance;
    step_ = Step::done;
  }

  Eigen::VectorXd b_, x_;
  GmresOptions options_;
  int m_ = 1;
  double norm_b_ = 0.0, beta_ = 0.0;
  bool after_update_ = false;
  Step step_ = Step::residual;
  Eigen::MatrixXd basis_, h_;
  Eigen::VectorXd cs_, sn_, g_;
  int k_ = 0;
  GmresResult result_;
};

}  // namespace

std::vector<GmresResult> gmres_columns(const ColumnsOperator& a,
                                       const ColumnsOperator& preconditioner,
                                       const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                                       const GmresOptions& options,
                                       const std::function<void(int, int, double)>& monitor) {
  const Eigen::Index n = b.rows(), count = b.cols();
  if (x.rows() != n || x.cols() != count) x = Eigen::MatrixXd::Zero(n, count);
  std::vector<ColumnGmres> columns;
  columns.reserve(static_cast<std::size_t>(count));
  for (Eigen::Index c = 0; c < count; ++c) columns.emplace_back(b.col(c), x.col(c), options);

  Eigen::MatrixXd u, z, t, w;
  std::vector<int> active;
  for (;;) {
    active.clear();
    Eigen::Index preconditioned = 0;
    for (int c = 0; c < int(count); ++c) {
      if (columns[size_t(c)].step() == ColumnGmres::Step::done) continue;
      active.push_back(c);
      if (columns[size_t(c)].wants_preconditioner()) ++preconditioned;
    }
    if (active.empty()) break;
    // One M⁻¹ for the columns that want it, then one A for every active column.
    u.resize(n, preconditioned);
    Eigen::Index j = 0;
    for (const int c : active)
      if (columns[size_t(c)].wants_preconditioner()) u.col(j++) = columns[size_t(c)].preconditioner_input();
    if (preconditioned > 0) {
      if (preconditioner)
        preconditioner(u, z);
      else
        z = u;
    }
    t.resize(n, Eigen::Index(active.size()));
    j = 0;
    for (std::size_t i = 0; i < active.size(); ++i) {
      ColumnGmres& column = columns[size_t(active[i])];
      t.col(Eigen::Index(i)) = column.wants_preconditioner()
                                   ? column.operand(z.col(j++))
                                   : column.operand(Eigen::VectorXd());
    }
    a(t, w);
    for (std::size_t i = 0; i < active.size(); ++i)
      columns[size_t(active[i])].take(w.col(Eigen::Index(i)), monitor, active[i]);
  }

  std::vector<GmresResult> results;
  for (Eigen::Index c = 0; c < count; ++c) {
    x.col(c) = columns[size_t(c)].solution();
    results.push_back(columns[size_t(c)].result());
  }
  return results;
}

GmresResult gmres(const LinearOperator& a, const LinearOperator& preconditioner,
                  const Eigen::VectorXd& b, Eigen::VectorXd& x, const GmresOptions& options,
                  const std::function<void(int iteration, double residual)>& monitor) {
  // One column: the columns operators apply the vector operators column by column.
  const auto by_columns = [](const LinearOperator& op) -> ColumnsOperator {
    if (!op) return {};
    return [&op](const Eigen::MatrixXd& in, Eigen::MatrixXd& out) {
      Eigen::VectorXd v, y;
      for (Eigen::Index c = 0; c < in.cols(); ++c) {
        v = in.col(c);
        op(v, y);
        if (c == 0) out.resize(y.size(), in.cols());
        out.col(c) = y;
      }
    };
  };
  Eigen::MatrixXd xs = Eigen::MatrixXd::Zero(b.size(), 1);
  if (x.size() == b.size()) xs.col(0) = x;
  const auto results = gmres_columns(
      by_columns(a), by_columns(preconditioner), b, xs, options,
      monitor ? std::function<void(int, int, double)>(
                    [&monitor](int, int iteration, double residual) { monitor(iteration, residual); })
              : std::function<void(int, int, double)>());
  x = xs.col(0);
  return results.front();
}

}  // namespace bemshape::bem
