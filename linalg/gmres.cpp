#include "linalg/gmres.hpp"

#include <cmath>

#include <Eigen/Dense>

namespace bemshape::linalg {
namespace {

/// An Arnoldi vector shorter than this fraction of its operator image before
/// orthogonalisation is a breakdown: the image lies in the Krylov space already (to rounding).
constexpr double kBreakdown = 1e-14;

/// Which operator a column wants applied next, if any.
enum class Wants { a, m, nothing };

/// One column's restarted GMRES, advanced one operator application at a time by the driver
/// below: the column names the operator it wants (A or M⁻¹) and its input, and is handed the
/// result. The steps, with Kₖ the Krylov basis v₀ … vₖ₋₁:
///
///   right preconditioning                       left preconditioning
///   residual  r = b − A x                       residual  r = M⁻¹(b − A x)     (A, then M⁻¹)
///   Arnoldi   w = A (M⁻¹ vₖ)    (M⁻¹, then A)   Arnoldi   w = M⁻¹(A vₖ)        (A, then M⁻¹)
///   update    x += M⁻¹(Kₖ yₖ)   (M⁻¹)           update    x += Kₖ yₖ           (no operator)
///
/// The left-preconditioned run first needs M⁻¹b, the scale of its residual.
class ColumnGmres {
 public:
  ColumnGmres(Eigen::VectorXd b, Eigen::VectorXd x, const GmresOptions& options)
      : b_(std::move(b)), x_(std::move(x)), options_(options), m_(std::max(1, options.restart)),
        left_(options.side == PreconditionerSide::left) {
    norm_b_ = b_.norm();
    true_norm_ = norm_b_;  // the residual of x = 0, until one is computed
    if (norm_b_ == 0.0) {
      x_.setZero();
      result_.converged = true;
      wants_ = Wants::nothing;
    } else if (left_) {
      input_ = b_;  // M⁻¹b first
      next_ = Next::scale;
      wants_ = Wants::m;
    } else if (x_.isZero(0.0)) {
      start_cycle(b_);  // A·0 = 0: no product needed
    } else {
      request_residual();
    }
  }

  Wants wants() const { return wants_; }
  bool done() const { return wants_ == Wants::nothing; }
  const Eigen::VectorXd& input() const { return input_; }

  /// Takes the result of the operator wants() named, applied to input(), and moves on.
  void receive(const Eigen::Ref<const Eigen::VectorXd>& result,
               const std::function<void(int, int, double)>& monitor, int column) {
    switch (next_) {
      case Next::scale:  // result = M⁻¹b
        norm_scale_ = result.norm();
        if (!(norm_scale_ > 0.0)) {  // M⁻¹ annihilates b (or NaN): nothing to measure against
          finish();
        } else if (x_.isZero(0.0)) {
          start_cycle(result);
        } else {
          request_residual();
        }
        return;
      case Next::residual: {  // result = A x
        Eigen::VectorXd r = b_ - result;
        true_norm_ = r.norm();
        if (left_) {
          input_ = std::move(r);
          next_ = Next::preconditioned_residual;
          wants_ = Wants::m;
        } else {
          start_cycle(r);
        }
        return;
      }
      case Next::preconditioned_residual:  // result = M⁻¹(b − A x)
        start_cycle(result);
        return;
      case Next::arnoldi_operand:  // right: result = M⁻¹vₖ; left: result = A vₖ
        input_ = result;
        next_ = Next::arnoldi;
        wants_ = left_ ? Wants::m : Wants::a;
        return;
      case Next::arnoldi:  // result = the image of vₖ
        arnoldi(result, monitor, column);
        return;
      case Next::correction:  // right only: result = M⁻¹(Kₖ yₖ)
        x_ += result;
        after_update_ = true;
        request_residual();
        return;
    }
  }

  const Eigen::VectorXd& solution() const { return x_; }
  const GmresResult& result() const { return result_; }

 private:
  enum class Next { scale, residual, preconditioned_residual, arnoldi_operand, arnoldi, correction };

  /// The norm the tolerance applies to: ‖b‖, or ‖M⁻¹b‖ when preconditioned on the left.
  double reference_norm() const { return left_ ? norm_scale_ : norm_b_; }

  void request_residual() {
    input_ = x_;
    next_ = Next::residual;
    wants_ = Wants::a;
  }

  /// r: the (preconditioned, on the left) residual of the current x.
  void start_cycle(const Eigen::Ref<const Eigen::VectorXd>& r) {
    const double new_beta = r.norm();
    if (after_update_ && !(new_beta < beta_)) {  // stagnation (or NaN): a restart won't help
      beta_ = new_beta;
      finish();
      return;
    }
    beta_ = new_beta;
    if (!(beta_ > options_.tolerance * reference_norm()) ||
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
    request_arnoldi();
  }

  void request_arnoldi() {
    input_ = basis_.col(k_);
    next_ = Next::arnoldi_operand;
    wants_ = left_ ? Wants::a : Wants::m;
  }

  void arnoldi(const Eigen::Ref<const Eigen::VectorXd>& product,
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
    if (!(rho > kBreakdown * w_before)) {  // the image adds nothing: keep the first k steps
      end_cycle();
      return;
    }
    cs_(k) = h_(k, k) / rho;
    sn_(k) = h_(k + 1, k) / rho;
    h_(k, k) = rho;
    h_(k + 1, k) = 0.0;
    g_(k + 1) = -sn_(k) * g_(k);
    g_(k) = cs_(k) * g_(k);
    const double estimate = std::abs(g_(k + 1)) / reference_norm();
    if (monitor) monitor(column, result_.iterations, estimate);
    ++k_;
    if (estimate <= options_.tolerance || !(w_norm > kBreakdown * w_before)) {
      end_cycle();  // converged, or the Krylov space is invariant (the residual cannot shrink)
      return;
    }
    basis_.col(k_) = w / w_norm;
    if (k_ < m_ && result_.iterations < options_.max_iterations)
      request_arnoldi();
    else
      end_cycle();
  }

  /// The cycle's correction Kₖ yₖ, yₖ solving the rotated least-squares problem Hₖ yₖ = gₖ.
  void end_cycle() {
    if (k_ == 0) {
      finish();  // no usable direction
      return;
    }
    const Eigen::VectorXd y =
        h_.topLeftCorner(k_, k_).triangularView<Eigen::Upper>().solve(g_.head(k_));
    if (left_) {
      x_ += basis_.leftCols(k_) * y;
      after_update_ = true;
      request_residual();
    } else {
      input_ = basis_.leftCols(k_) * y;
      next_ = Next::correction;
      wants_ = Wants::m;
    }
  }

  void finish() {
    result_.residual = true_norm_ / norm_b_;
    result_.preconditioned_residual =
        left_ && norm_scale_ > 0.0 ? beta_ / norm_scale_ : result_.residual;
    result_.converged =
        (left_ ? result_.preconditioned_residual : result_.residual) <= options_.tolerance;
    wants_ = Wants::nothing;
  }

  Eigen::VectorXd b_, x_, input_;
  GmresOptions options_;
  int m_ = 1;
  bool left_ = false;
  double norm_b_ = 0.0, norm_scale_ = 0.0, beta_ = 0.0, true_norm_ = 0.0;
  bool after_update_ = false;
  Wants wants_ = Wants::nothing;
  Next next_ = Next::residual;
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

  // Each round applies M⁻¹ once to the columns that want it, then A once to the columns
  // that want it (a column handed M⁻¹'s result may want A in the same round).
  Eigen::MatrixXd in, out;
  std::vector<int> asking;
  const auto apply = [&](Wants which, const ColumnsOperator& op) {
    asking.clear();
    for (int c = 0; c < int(count); ++c)
      if (columns[size_t(c)].wants() == which) asking.push_back(c);
    if (asking.empty()) return;
    in.resize(n, Eigen::Index(asking.size()));
    for (std::size_t i = 0; i < asking.size(); ++i)
      in.col(Eigen::Index(i)) = columns[size_t(asking[i])].input();
    if (op)
      op(in, out);
    else
      out = in;  // no preconditioner: the identity
    for (std::size_t i = 0; i < asking.size(); ++i)
      columns[size_t(asking[i])].receive(out.col(Eigen::Index(i)), monitor, asking[i]);
  };
  for (;;) {
    bool all_done = true;
    for (const ColumnGmres& column : columns) all_done = all_done && column.done();
    if (all_done) break;
    apply(Wants::m, preconditioner);
    apply(Wants::a, a);
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

}  // namespace bemshape::linalg
