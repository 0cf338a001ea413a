#include "optimal/optimal_control.hpp"

#include <algorithm>
#include <exception>
#include <string>
#include <vector>

#include "IpTNLP.hpp"
#include "core/error.hpp"
#include "optimal/shooting_interval.hpp"

namespace thetad {

namespace {

constexpr double kNoBound = 1e20;  // beyond Ipopt's nlp_*_bound_inf (1e19): no bound

// z = [node_0, u_0, node_1, u_1, ..., node_{N-1}, u_{N-1}, node_N]; constraint block k is
// interval map(node_k, u_k) − node_{k+1} = 0.
class ShootingNlp final : public Ipopt::TNLP {
 public:
  ShootingNlp(const OptimalControlProblem& problem, const ShootingTrajectory& start,
              const OptimalControlSettings& settings)
      : problem_(problem),
        settings_(settings),
        start_(start),
        interval_(problem),
        intervals_(problem.intervals),
        d_(problem.node_dim()),
        m_(problem.plant->input_dim()),
        next_(static_cast<std::size_t>(intervals_), Eigen::VectorXd(d_)),
        costs_(static_cast<std::size_t>(intervals_)),
        derivatives_(static_cast<std::size_t>(intervals_)),
        node_(d_),
        u_(m_) {}

  int variables() const { return intervals_ * (d_ + m_) + d_; }
  int node_offset(int k) const { return k * (d_ + m_); }
  const std::vector<double>& solution() const { return solution_; }
  int iterations() const { return iterations_; }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g, Ipopt::Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = variables();
    m = intervals_ * d_;
    nnz_jac_g = intervals_ * (d_ * (d_ + m_) + d_);
    nnz_h_lag = 0;  // limited-memory Hessian
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m, Ipopt::Number* g_l,
                       Ipopt::Number* g_u) override {
    std::fill(x_l, x_l + n, -kNoBound);
    std::fill(x_u, x_u + n, kNoBound);
    const Eigen::VectorXd first = interval_.initial_node();
    for (int i = 0; i < d_; ++i) x_l[i] = x_u[i] = first[i];
    if (problem_.bounded()) {
      for (int k = 0; k < intervals_; ++k) {
        Eigen::Map<Eigen::VectorXd>(x_l + node_offset(k) + d_, m_) = problem_.input_lower;
        Eigen::Map<Eigen::VectorXd>(x_u + node_offset(k) + d_, m_) = problem_.input_upper;
      }
    }
    std::fill(g_l, g_l + m, 0.0);
    std::fill(g_u, g_u + m, 0.0);
    return true;
  }

  // Every unknown scaled by sqrt(w T) with w its weight in J (the smallest positive weight where it
  // has none) and T the interval's length, so that J's curvature is about 1 in each: the
  // weights span 1 to 1e7 on the helicopter, far too wide for an L-BFGS Hessian started from a
  // multiple of the identity. A defect row takes its state's scale.
  bool get_scaling_parameters(Ipopt::Number& obj_scaling, bool& use_x_scaling, Ipopt::Index, Ipopt::Number* x_scaling,
                              bool& use_g_scaling, Ipopt::Index, Ipopt::Number* g_scaling) override {
    const double length = problem_.interval_periods * problem_.controller_period();
    const auto scales = [length](const Eigen::VectorXd& weights) {
      const double positive = (weights.array() > 0.0).select(weights.array(), weights.maxCoeff()).minCoeff();
      return Eigen::VectorXd(((weights.array() > 0.0).select(weights.array(), positive) * length).sqrt());
    };
    Eigen::VectorXd node_scale(d_);
    node_scale.head(problem_.plant->state_dim()) = scales(problem_.state_weights);
    if (problem_.sampled_position_integral)
      node_scale.tail<3>() = node_scale.segment<3>(*problem_.sampled_position_integral);
    const Eigen::VectorXd input_scale = scales(problem_.input_weights);
    for (int k = 0; k <= intervals_; ++k) {
      Eigen::Map<Eigen::VectorXd>(x_scaling + node_offset(k), d_) = node_scale;
      if (k < intervals_) Eigen::Map<Eigen::VectorXd>(x_scaling + node_offset(k) + d_, m_) = input_scale;
      if (k < intervals_) Eigen::Map<Eigen::VectorXd>(g_scaling + k * d_, d_) = node_scale;
    }
    obj_scaling = 1.0;
    use_x_scaling = use_g_scaling = true;
    return true;
  }

  bool get_starting_point(Ipopt::Index, bool, Ipopt::Number* x, bool, Ipopt::Number*, Ipopt::Number*, Ipopt::Index,
                          bool, Ipopt::Number*) override {
    for (int k = 0; k <= intervals_; ++k) {
      Eigen::Map<Eigen::VectorXd>(x + node_offset(k), d_) = start_.nodes.row(k).transpose();
      if (k < intervals_) Eigen::Map<Eigen::VectorXd>(x + node_offset(k) + d_, m_) = start_.inputs.row(k).transpose();
    }
    // The first node is fixed: the initial state, whatever the guess says.
    Eigen::Map<Eigen::VectorXd>(x, d_) = interval_.initial_node();
    return true;
  }

  bool eval_f(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Number& obj_value) override {
    if (!values(x, new_x)) return false;
    obj_value = 0.0;
    for (const double c : costs_) obj_value += c;
    return true;
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Number* grad_f) override {
    if (!derivatives(x, new_x)) return false;
    std::fill(grad_f, grad_f + n, 0.0);
    for (int k = 0; k < intervals_; ++k) {
      const Eigen::MatrixXd& J = derivatives_[static_cast<std::size_t>(k)];
      Eigen::Map<Eigen::VectorXd>(grad_f + node_offset(k), d_ + m_) = J.row(d_).transpose();
    }
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Index, Ipopt::Number* g) override {
    if (!values(x, new_x)) return false;
    for (int k = 0; k < intervals_; ++k) {
      Eigen::Map<Eigen::VectorXd>(g + k * d_, d_) =
          next_[static_cast<std::size_t>(k)] - Eigen::Map<const Eigen::VectorXd>(x + node_offset(k + 1), d_);
    }
    return true;
  }

  // Per block k, row-major over its d rows: the d + m columns of (node_k, u_k), then the −1 on
  // node_{k+1}'s diagonal.
  bool eval_jac_g(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Index, Ipopt::Index, Ipopt::Index* iRow,
                  Ipopt::Index* jCol, Ipopt::Number* values) override {
    const int width = d_ + m_;
    int entry = 0;
    if (values == nullptr) {
      for (int k = 0; k < intervals_; ++k) {
        for (int i = 0; i < d_; ++i) {
          for (int j = 0; j < width; ++j, ++entry) {
            iRow[entry] = k * d_ + i;
            jCol[entry] = node_offset(k) + j;
          }
          iRow[entry] = k * d_ + i;
          jCol[entry++] = node_offset(k + 1) + i;
        }
      }
      return true;
    }
    if (!derivatives(x, new_x)) return false;
    for (int k = 0; k < intervals_; ++k) {
      const Eigen::MatrixXd& J = derivatives_[static_cast<std::size_t>(k)];
      for (int i = 0; i < d_; ++i) {
        for (int j = 0; j < width; ++j) values[entry++] = J(i, j);
        values[entry++] = -1.0;
      }
    }
    return true;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Ipopt::Index iter, Ipopt::Number obj_value, Ipopt::Number inf_pr,
                             Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number,
                             Ipopt::Number, Ipopt::Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    iterations_ = iter;
    if (!settings_.progress) return true;
    // What progress throws (a Ctrl-C from Python) stops Ipopt as a user's stop and is thrown
    // again once Ipopt has returned: an exception must not cross Ipopt's frames.
    try {
      settings_.progress(iter, obj_value, inf_pr);
    } catch (...) {
      stopped_by_ = std::current_exception();
      return false;
    }
    return true;
  }

  void rethrow_stop() const {
    if (stopped_by_) std::rethrow_exception(stopped_by_);
  }

  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index n, const Ipopt::Number* x, const Ipopt::Number*,
                         const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*, const Ipopt::Number*,
                         Ipopt::Number, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution_.assign(x, x + n);
  }

 private:
  void unpack(const Ipopt::Number* x, int k) {
    node_ = Eigen::Map<const Eigen::VectorXd>(x + node_offset(k), d_);
    u_ = Eigen::Map<const Eigen::VectorXd>(x + node_offset(k) + d_, m_);
  }

  // Runs `fill` on every interval at x once per point (Ipopt's new_x says when x changed); false
  // where the plant has no value there.
  template <class Fill>
  bool once_per_point(const Ipopt::Number* x, bool new_x, bool& have, const Fill& fill) {
    if (new_x) have_values_ = have_derivatives_ = false;
    if (have) return true;
    try {
      for (int k = 0; k < intervals_; ++k) {
        unpack(x, k);
        fill(static_cast<std::size_t>(k));
      }
    } catch (const Error&) {
      return false;
    }
    return have = true;
  }

  // The intervals' ends and costs.
  bool values(const Ipopt::Number* x, bool new_x) {
    return once_per_point(x, new_x, have_values_, [this](std::size_t k) {
      costs_[k] = interval_.propagate(static_cast<int>(k), node_, u_, next_[k]);
    });
  }

  // The derivatives, and the values with them.
  bool derivatives(const Ipopt::Number* x, bool new_x) {
    const bool done = once_per_point(x, new_x, have_derivatives_, [this](std::size_t k) {
      costs_[k] = interval_.linearize(static_cast<int>(k), node_, u_, next_[k], derivatives_[k]);
    });
    if (done) have_values_ = true;
    return done;
  }

  const OptimalControlProblem& problem_;
  const OptimalControlSettings& settings_;
  const ShootingTrajectory& start_;
  ShootingInterval interval_;
  int intervals_, d_, m_;
  std::vector<Eigen::VectorXd> next_;
  std::vector<double> costs_;
  std::vector<Eigen::MatrixXd> derivatives_;
  Eigen::VectorXd node_, u_;
  bool have_values_ = false, have_derivatives_ = false;
  std::vector<double> solution_;
  int iterations_ = 0;
  std::exception_ptr stopped_by_;
};

void check_shape(const char* what, const Eigen::MatrixXd& matrix, Eigen::Index rows, Eigen::Index cols) {
  if (matrix.rows() != rows || matrix.cols() != cols)
    throw Error(std::string("optimal control: ") + what + " is " + std::to_string(matrix.rows()) + "x" +
                std::to_string(matrix.cols()) + ", expected " + std::to_string(rows) + "x" + std::to_string(cols));
  if (!matrix.allFinite()) throw Error(std::string("optimal control: ") + what + " is not finite");
}

}  // namespace

ShootingTrajectory shooting_guess(const OptimalControlProblem& problem, const Eigen::MatrixXd& states,
                                  const Eigen::MatrixXd& inputs) {
  problem.validate();
  const int n = problem.plant->state_dim(), m = problem.plant->input_dim(), samples = problem.samples();
  if (states.rows() < samples || inputs.rows() < samples || states.cols() != n || inputs.cols() != m) {
    throw Error("optimal control: the warm start has " + std::to_string(states.rows()) + " samples of " +
                std::to_string(states.cols()) + " states and " + std::to_string(inputs.rows()) + " of " +
                std::to_string(inputs.cols()) + " inputs; the horizon needs " + std::to_string(samples) + " samples of " +
                std::to_string(n) + " and " + std::to_string(m));
  }
  const int K = problem.interval_periods, N = problem.intervals, d = problem.node_dim();
  const double period = problem.controller_period();
  ShootingTrajectory guess{Eigen::MatrixXd(N + 1, d), Eigen::MatrixXd(N, m)};
  PositionIntegral error_integral;
  error_integral.value = problem.initial_integral;
  for (int k = 0; k < N; ++k) {
    guess.nodes.row(k).head(n) = states.row(k * K);
    if (problem.sampled_position_integral) guess.nodes.row(k).tail<3>() = error_integral.value.transpose();
    guess.inputs.row(k) = inputs.middleRows(k * K, K).colwise().mean();
    for (int j = k * K; j < (k + 1) * K; ++j) {
      const Eigen::Vector3d position = states.row(j).head<3>().transpose();
      error_integral.accumulate(position - problem.reference->position((problem.first_sample + j) * period), period);
    }
  }
  ShootingInterval interval(problem);
  Eigen::VectorXd last(d);
  interval.propagate(N - 1, guess.nodes.row(N - 1).transpose(), guess.inputs.row(N - 1).transpose(), last);
  guess.nodes.row(N) = last.transpose();
  return guess;
}

OptimalControlSolution solve_optimal_control(const OptimalControlProblem& problem, const ShootingTrajectory& start,
                                             const OptimalControlSettings& settings) {
  problem.validate();
  const int N = problem.intervals, d = problem.node_dim(), n = problem.plant->state_dim(),
            m = problem.plant->input_dim();
  check_shape("the start's nodes", start.nodes, N + 1, d);
  check_shape("the start's inputs", start.inputs, N, m);

  {  // A plant without a Jacobian, or without a value at the start, fails here with its reason, not in Ipopt.
    ShootingInterval first(problem);
    Eigen::VectorXd next;
    Eigen::MatrixXd derivative;
    first.linearize(0, first.initial_node(), start.inputs.row(0).transpose(), next, derivative);
  }
  Ipopt::SmartPtr<ShootingNlp> nlp = new ShootingNlp(problem, start, settings);
  OptimalControlSolution solution;
  solution.outcome = solve_with_ipopt(*nlp, settings.ipopt);
  nlp->rethrow_stop();
  solution.iterations = nlp->iterations();
  if (nlp->solution().empty()) {
    throw Error("optimal control: Ipopt stopped before its first iterate (status " + solution.outcome.status +
                "): the plant has no value along the warm start");
  }
  const double* z = nlp->solution().data();
  solution.shooting = {Eigen::MatrixXd(N + 1, d), Eigen::MatrixXd(N, m)};
  for (int k = 0; k <= N; ++k) {
    solution.shooting.nodes.row(k) = Eigen::Map<const Eigen::RowVectorXd>(z + nlp->node_offset(k), d);
    if (k < N) solution.shooting.inputs.row(k) = Eigen::Map<const Eigen::RowVectorXd>(z + nlp->node_offset(k) + d, m);
  }

  ShootingInterval interval(problem);
  solution.samples.resize(problem.samples(), 1 + n + m + n);
  Eigen::Index row = 0;
  const auto record = [&](double t, const Eigen::VectorXd& node, const Eigen::VectorXd& v, const Eigen::VectorXd& u) {
    solution.samples.row(row++) << t, node.head(n).transpose(), u.transpose(), v.transpose();
  };
  Eigen::VectorXd next(d);
  for (int k = 0; k < N; ++k) {
    solution.cost += interval.propagate(k, solution.shooting.nodes.row(k).transpose(),
                                        solution.shooting.inputs.row(k).transpose(), next, record);
    solution.constraint_violation = std::max(
        solution.constraint_violation, (next - solution.shooting.nodes.row(k + 1).transpose()).cwiseAbs().maxCoeff());
  }
  return solution;
}

}  // namespace thetad
