#include "core/trim.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include <Eigen/Geometry>

#include "IpTNLP.hpp"
#include "core/error.hpp"
#include "core/ipopt_solve.hpp"

namespace thetad {

TrimCondition TrimCondition::hover(double altitude, double heading) {
  return straight(0.0, 0.0, 0.0, altitude, heading);
}

TrimCondition TrimCondition::straight(double speed, double course, double climb_rate, double altitude,
                                      double heading) {
  TrimCondition condition;
  condition.position_ned = Eigen::Vector3d(0.0, 0.0, -altitude);
  condition.velocity_ned = Eigen::Vector3d(speed * std::cos(course), speed * std::sin(course), -climb_rate);
  condition.heading = heading;
  return condition;
}

namespace {

using namespace heli;

// The NLP (why this shape):
// - Unknowns z = [phi, theta, a1, b1, T_mr/(m g), delta_ped, delta_col, delta_lon, delta_lat].
//   In straight flight p = q = r = 0 and psi is commanded, and the body velocity is not free: it is
//   R(phi, theta, psi)^T V_ned, so it is computed from the attitude instead of being an unknown
//   tied to V_ned by three more constraints. T_mr is scaled by the weight so that every unknown
//   is O(0.1..1) (Ipopt does not scale variables).
// - Constraints: the 8 rows u, v, w, p, q, r, a1, b1 of f = 0. The position rows then equal V_ned
//   and the Euler rows vanish by construction; as constraints they would be identically
//   satisfied, i.e. zero Jacobian rows, which makes the constraint Jacobian rank deficient.
// - Objective delta_col^2: 8 equations in 9 unknowns leave one direction free, because delta_col
//   only enters the flapping rows through u_a delta_col and v_a delta_col (docs/model.md §3.5), where it
//   duplicates the cyclic (A-2; in hover it has no effect at all). The controllers penalize
//   delta_col by far the most (R = 1e7), so the trim they hold is the one with least collective:
//   the minimum is delta_col = 0 wherever the remaining 8x8 system has a root, which is also how
//   docs/model.md §13 defines the hover trim. No other regularization is needed: with delta_col fixed the
//   other 8 unknowns are determined (nonsingular Jacobian), so the minimizer is unique.
enum Unknown : int { kUnkPhi, kUnkTheta, kUnkA1, kUnkB1, kUnkThrust, kUnkPed, kUnkCol, kUnkLon, kUnkLat };
constexpr int kUnknowns = 9;
constexpr std::array<int, 8> kEquilibriumRows = {kU, kV, kW, kP, kQ, kR, kA1, kB1};
constexpr int kConstraints = static_cast<int>(kEquilibriumRows.size());

// Keeps the attitude well away from the Euler singularity theta = +-pi/2 (docs/model.md §3.4) and the
// thrust positive, where A4 has a rotor speed.
constexpr double kMaxAttitude = 1.2;        // rad
constexpr double kMinThrustFraction = 1e-3;  // of m g
constexpr double kNoBound = 1e20;           // beyond Ipopt's nlp_*_bound_inf (1e19): no bound

Eigen::Matrix3d body_to_ned(double phi, double theta, double psi) {  // R(Theta) of Eq. 2
  return (Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

std::string to_text(double value) {
  std::ostringstream out;
  out << std::setprecision(3) << value;
  return out.str();
}

// Maps unknowns to (x, u) and evaluates the equilibrium equations.
class TrimEquations {
 public:
  TrimEquations(const Helicopter& plant, const TrimCondition& condition)
      : plant_(plant),
        condition_(condition),
        weight_(plant.parameters().mass * plant.parameters().gravity),
        x_(kStateDim),
        u_(kInputDim),
        xdot_(kStateDim) {}

  double weight() const { return weight_; }

  void point(const double* z, Eigen::VectorXd& x, Eigen::VectorXd& u) const {
    x.setZero(kStateDim);
    x.segment<3>(kXp) = condition_.position_ned;
    x.segment<3>(kU) = body_to_ned(z[kUnkPhi], z[kUnkTheta], condition_.heading).transpose() * condition_.velocity_ned;
    x[kPhi] = z[kUnkPhi];
    x[kTheta] = z[kUnkTheta];
    x[kPsi] = condition_.heading;
    x[kA1] = z[kUnkA1];
    x[kB1] = z[kUnkB1];
    x[kS] = 1.0;  // bias state at its initial value (Eq. 26); it does not enter f's physical rows
    u.resize(kInputDim);
    u << z[kUnkThrust] * weight_, z[kUnkPed], z[kUnkCol], z[kUnkLon], z[kUnkLat];
  }

  // Why the last evaluation that failed had no value.
  const std::string& last_error() const { return last_error_; }

  // False where f has no value (no A4 rotor speed for this thrust and airspeed) or is not finite:
  // Ipopt then shortens its step.
  bool evaluate(const double* z, double* c) {
    point(z, x_, u_);
    try {
      plant_.f(x_, u_, xdot_);
    } catch (const Error& e) {
      last_error_ = e.what();
      return false;
    }
    for (int i = 0; i < kConstraints; ++i) {
      c[i] = xdot_[kEquilibriumRows[static_cast<std::size_t>(i)]];
      if (!std::isfinite(c[i])) return false;
    }
    return true;
  }

  // Dense Jacobian (row-major, kConstraints x kUnknowns) by central differences with the step
  // eps^(1/3) max(1, |z_j|) that balances truncation (h^2) against rounding (eps/h): about 1e-10
  // relative accuracy, enough for Ipopt's Newton steps (the solution itself only depends on c).
  // One-sided where one side has no value (near the end of A4's rotor-speed bracket).
  bool jacobian(const double* z, double* values) {
    const double step_scale = std::cbrt(std::numeric_limits<double>::epsilon());
    std::array<double, kUnknowns> zp{};
    std::array<double, kConstraints> c0{}, cp{}, cm{};
    bool have_c0 = false;
    for (int j = 0; j < kUnknowns; ++j) {
      std::copy(z, z + kUnknowns, zp.begin());
      const double h = step_scale * std::max(1.0, std::abs(z[j]));
      zp[static_cast<std::size_t>(j)] = z[j] + h;
      const bool plus = evaluate(zp.data(), cp.data());
      zp[static_cast<std::size_t>(j)] = z[j] - h;
      const bool minus = evaluate(zp.data(), cm.data());
      double span = 2.0 * h;
      if (plus != minus) {
        if (!have_c0 && !(have_c0 = evaluate(z, c0.data()))) return false;
        (plus ? cm : cp) = c0;
        span = h;
      } else if (!plus) {
        return false;
      }
      for (int i = 0; i < kConstraints; ++i) {
        const auto k = static_cast<std::size_t>(i);
        values[i * kUnknowns + j] = (cp[k] - cm[k]) / span;
      }
    }
    return true;
  }

 private:
  const Helicopter& plant_;
  const TrimCondition& condition_;
  double weight_;
  Eigen::VectorXd x_, u_, xdot_;
  std::string last_error_ = "f is not finite";
};

class TrimNlp final : public Ipopt::TNLP {
 public:
  TrimNlp(TrimEquations& equations, const std::array<double, kUnknowns>& start)
      : equations_(equations), start_(start) {}

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g, Ipopt::Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = kUnknowns;
    m = kConstraints;
    nnz_jac_g = kUnknowns * kConstraints;
    nnz_h_lag = 0;  // limited-memory Hessian
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index, Ipopt::Number* g_l,
                       Ipopt::Number* g_u) override {
    for (int j = 0; j < kUnknowns; ++j) {
      x_l[j] = -kNoBound;
      x_u[j] = kNoBound;
    }
    x_l[kUnkPhi] = x_l[kUnkTheta] = -kMaxAttitude;
    x_u[kUnkPhi] = x_u[kUnkTheta] = kMaxAttitude;
    x_l[kUnkThrust] = kMinThrustFraction;
    for (int i = 0; i < kConstraints; ++i) g_l[i] = g_u[i] = 0.0;
    return true;
  }

  bool get_starting_point(Ipopt::Index, bool, Ipopt::Number* x, bool, Ipopt::Number*, Ipopt::Number*, Ipopt::Index,
                          bool, Ipopt::Number*) override {
    std::copy(start_.begin(), start_.end(), x);
    return true;
  }

  bool eval_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number& obj_value) override {
    obj_value = x[kUnkCol] * x[kUnkCol];
    return true;
  }

  bool eval_grad_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number* grad_f) override {
    std::fill(grad_f, grad_f + kUnknowns, 0.0);
    grad_f[kUnkCol] = 2.0 * x[kUnkCol];
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index, Ipopt::Number* g) override {
    return equations_.evaluate(x, g);
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index, Ipopt::Index, Ipopt::Index* iRow,
                  Ipopt::Index* jCol, Ipopt::Number* values) override {
    if (values == nullptr) {
      for (int i = 0; i < kConstraints; ++i) {
        for (int j = 0; j < kUnknowns; ++j) {
          iRow[i * kUnknowns + j] = i;
          jCol[i * kUnknowns + j] = j;
        }
      }
      return true;
    }
    return equations_.jacobian(x, values);
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Ipopt::Index iter, Ipopt::Number, Ipopt::Number, Ipopt::Number,
                             Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number,
                             Ipopt::Index, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    iterations_ = iter;  // counts restoration-phase iterations too, unlike a null Statistics()
    return true;
  }

  // The constraints are re-evaluated here rather than read from Ipopt's g, which holds no values
  // when the very first evaluation failed.
  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index, const Ipopt::Number* x, const Ipopt::Number*,
                         const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*, const Ipopt::Number*,
                         Ipopt::Number, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    std::copy(x, x + kUnknowns, solution_.begin());
    std::array<double, kConstraints> g{};
    has_value_ = equations_.evaluate(x, g.data());
    constraint_violation_ = 0.0;
    for (const double gi : g) constraint_violation_ = std::max(constraint_violation_, std::abs(gi));
    finalized_ = true;
  }

  bool finalized() const { return finalized_; }
  bool has_value() const { return has_value_; }
  const std::array<double, kUnknowns>& solution() const { return solution_; }
  double constraint_violation() const { return constraint_violation_; }
  int iterations() const { return iterations_; }

 private:
  TrimEquations& equations_;
  std::array<double, kUnknowns> start_;
  std::array<double, kUnknowns> solution_{};
  double constraint_violation_ = std::numeric_limits<double>::quiet_NaN();
  int iterations_ = 0;
  bool finalized_ = false;
  bool has_value_ = false;
};

std::string describe(const TrimCondition& c) {
  std::ostringstream out;
  // "+ 0.0" prints a negative zero (a zero climb rate negated) as 0.
  out << "trim at V_ned = (" << c.velocity_ned.x() + 0.0 << ", " << c.velocity_ned.y() + 0.0 << ", "
      << c.velocity_ned.z() + 0.0
      << ") m/s, heading " << c.heading << " rad, altitude " << -c.position_ned.z() << " m";
  return out.str();
}

}  // namespace

Trim find_trim(const heli::Helicopter& plant, const TrimCondition& condition, const TrimOptions& options) {
  TrimEquations equations(plant, condition);

  std::array<double, kUnknowns> start{};
  start[kUnkThrust] = 1.0;
  if (options.initial_guess) {
    const Trim& guess = *options.initial_guess;
    if (guess.state.size() != kStateDim || guess.input.size() != kInputDim) {
      throw Error("find_trim: the initial guess has " + std::to_string(guess.state.size()) + " states and " +
                  std::to_string(guess.input.size()) + " inputs; expected 18 and 5");
    }
    start = {guess.state[kPhi],  guess.state[kTheta], guess.state[kA1],  guess.state[kB1],
             guess.input[kTmr] / equations.weight(), guess.input[kPed], guess.input[kCol],
             guess.input[kLon], guess.input[kLat]};
  }

  Ipopt::SmartPtr<TrimNlp> nlp = new TrimNlp(equations, start);
  IpoptRun run;
  run.max_iterations = options.max_iterations;
  // Converge well below residual_tolerance: constraints are accelerations (m/s^2, rad/s^2)
  // whose rounding floor is ~1e-13.
  run.tolerance = 1e-12;
  run.constraint_tolerance = 1e-11;
  const IpoptOutcome outcome = solve_with_ipopt(*nlp, run);

  const std::string what = describe(condition);
  std::string report = "status " + outcome.status + ", " + std::to_string(nlp->iterations()) +
                       " iterations, ";
  if (!nlp->finalized() || !nlp->has_value()) {
    throw Error(what + ": Ipopt did not converge (" + report +
                "final constraint violation undefined: f has no value at the final iterate: " +
                equations.last_error() + ")");
  }
  report += "final constraint violation " + to_text(nlp->constraint_violation());
  if (!outcome.converged) {
    throw Error(what + ": Ipopt did not converge (" + report + ")");
  }

  Trim trim;
  equations.point(nlp->solution().data(), trim.state, trim.input);
  Eigen::VectorXd xdot(kStateDim);
  plant.f(trim.state, trim.input, xdot);
  xdot.segment<3>(kXp) -= condition.velocity_ned;
  trim.residual = xdot.head(kPhysicalStateDim).norm();
  trim.rotor_speed = plant.rotor_speed(trim.state, trim.input[kTmr]);
  trim.solver_status = outcome.status;
  trim.iterations = nlp->iterations();
  if (!(trim.residual <= options.residual_tolerance)) {
    throw Error(what + ": Ipopt's solution is not an equilibrium (" + report + ", ||f|| = " +
                to_text(trim.residual) + " > tolerance " + to_text(options.residual_tolerance) + ")");
  }
  return trim;
}

}  // namespace thetad
