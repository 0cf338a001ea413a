#include "controllers/weights_design.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <unsupported/Eigen/MatrixFunctions>

#include "controllers/linearization.hpp"
#include "controllers/theta_d.hpp"
#include "core/error.hpp"
#include "core/riccati.hpp"
#include "core/sim/actuator_limits.hpp"
#include "core/trim.hpp"
#include "core/trim_sweep.hpp"

namespace thetad {

namespace {

using namespace heli;
constexpr int kDesignStates = kStateDim - 1;  // V_track without the bias state s
constexpr double kHoverAltitude = 3.5;        // m: the trims' altitude (the model has no altitude dependence)
constexpr double kResponseTime = 3.0;         // s of each step and acceleration response
constexpr int kFrequencies = 120;             // of the disk-margin sweep, log-spaced up to Nyquist

// The responses whose peak input is checked: 1 m steps of the position error in x, y, h, then
// 1 m/s² of commanded acceleration along the body axes u, v, w.
enum Forcing : int { kStepX, kStepY, kStepH, kAccelerationX, kAccelerationY, kAccelerationZ, kForcings };
constexpr const char* kForcingNames[kForcings] = {"step in x", "step in y", "step in h",
                                                  "acceleration along x", "acceleration along y",
                                                  "acceleration along z"};
constexpr const char* kChannels[kInputDim] = {"T_mr", "delta_ped", "delta_col", "delta_lon", "delta_lat"};

// The weights a forcing's failure turns down: its axis's position and integral (steps), its
// velocity (accelerations).
std::vector<int> weights_of(int forcing) {
  switch (forcing) {
    case kStepX: return {kXp, kXi};
    case kStepY: return {kYp, kYi};
    case kStepH: return {kZp, kZi};
    case kAccelerationX: return {kU};
    case kAccelerationY: return {kV};
    default: return {kW};
  }
}

struct Point {
  std::string label;  // "speed 4 m/s, course 90 deg, climb 0 m/s"
  Eigen::VectorXd state, input;
};

// One closed loop's figures at one point and period.
struct LoopFigures {
  double spectral_radius = 0.0;
  // Unstable through a mode slower than a tenth of Nyquist: not the delay's doing, and no slower
  // loop (more R) can fix it.
  bool slow_unstable = false;
  double disk_margin = 0.0;
  std::array<double, kForcings> peak_share{};  // max_j |Δu_j| / headroom_j
  std::array<int, kForcings> peak_channel{};
};

// ZOH discretization of ẋ = A x + B u over T: Φ = e^{AT}, Γ = ∫_0^T e^{As} ds B.
void discretize(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double T, Eigen::MatrixXd& Phi,
                Eigen::MatrixXd& Gamma) {
  const Eigen::Index n = A.rows(), m = B.cols();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + m, n + m);
  M.topLeftCorner(n, n) = A * T;
  M.topRightCorner(n, m) = B * T;
  const Eigen::MatrixXd E = M.exp();
  Phi = E.topLeftCorner(n, n);
  Gamma = E.topRightCorner(n, m);
}

// u_k = −K x_{k−1}'s loop: the sampled plant with one sample of delay, z = [x_k; u_{k−1}].
LoopFigures check_loop(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& K, double T,
                       const Eigen::VectorXd& headroom) {
  const Eigen::Index n = A.rows(), m = B.cols();
  Eigen::MatrixXd Phi, Gamma, Phi_v, Gamma_v;
  discretize(A, B, T, Phi, Gamma);
  Eigen::MatrixXd velocity_rows = Eigen::MatrixXd::Zero(n, 3);
  velocity_rows.middleRows(kU, 3).setIdentity();
  discretize(A, velocity_rows, T, Phi_v, Gamma_v);
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(n + m, n + m);
  Z.topLeftCorner(n, n) = Phi;
  Z.topRightCorner(n, m) = Gamma;
  Z.bottomLeftCorner(m, n) = -K;
  LoopFigures figures;
  const Eigen::VectorXcd eigenvalues = Eigen::EigenSolver<Eigen::MatrixXd>(Z, false).eigenvalues();
  Eigen::Index largest = 0;
  figures.spectral_radius = eigenvalues.cwiseAbs().maxCoeff(&largest);
  if (figures.spectral_radius >= 1.0) {
    figures.slow_unstable = std::abs(std::log(eigenvalues[largest])) / T < 0.1 * std::numbers::pi / T;
    figures.peak_share.fill(std::numeric_limits<double>::infinity());
    return figures;
  }
  // Balanced disk margin (σ = 0): α = 1 / sup_ω μ(S − I/2), S = (I + L)⁻¹, L(z) = K (zI − Φ)⁻¹ Γ z⁻¹
  // broken at the plant input; μ is bounded by σ̄ in the channels scaled by the headroom (R^½ of
  // Bryson's start), so α is a lower bound of the multiloop margin.
  double worst = 0.0;
  const double nyquist = std::numbers::pi / T;
  const Eigen::VectorXcd scale = headroom.cwiseInverse().cast<std::complex<double>>();
  for (int k = 0; k < kFrequencies; ++k) {
    const double w = 0.01 * std::pow(nyquist / 0.01, static_cast<double>(k) / (kFrequencies - 1));
    const std::complex<double> z = std::polar(1.0, w * T);
    const Eigen::MatrixXcd resolvent = (z * Eigen::MatrixXcd::Identity(n, n) - Phi.cast<std::complex<double>>())
                                           .partialPivLu()
                                           .solve(Gamma.cast<std::complex<double>>());
    const Eigen::MatrixXcd L = K.cast<std::complex<double>>() * resolvent / z;
    const Eigen::MatrixXcd S = (Eigen::MatrixXcd::Identity(m, m) + L).inverse();
    // In the channels scaled by R^½ (the LQR's own scaling): μ ≤ σ̄(D M D⁻¹) for any diagonal D.
    const Eigen::MatrixXcd shifted =
        scale.asDiagonal() * (S - 0.5 * Eigen::MatrixXcd::Identity(m, m)) * scale.cwiseInverse().asDiagonal();
    worst = std::max(worst, Eigen::JacobiSVD<Eigen::MatrixXcd>(shifted).singularValues()(0));
  }
  figures.disk_margin = 1.0 / worst;
  // The responses, from rest (a step: the position error starts at 1 m) or under a constant
  // acceleration forcing of the velocity rows.
  const auto steps = static_cast<int>(std::lround(kResponseTime / T));
  for (int forcing = 0; forcing < kForcings; ++forcing) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n), u_previous = Eigen::VectorXd::Zero(m), drive = Eigen::VectorXd::Zero(n);
    if (forcing <= kStepH) x[forcing] = 1.0;
    else drive = Gamma_v.col(forcing - kAccelerationX);
    double peak = 0.0;
    int channel = 0;
    for (int k = 0; k < steps; ++k) {
      const Eigen::VectorXd u = -K * x;
      for (Eigen::Index j = 0; j < m; ++j) {
        const double share = std::abs(u[j]) / headroom[j];
        if (share > peak) {
          peak = share;
          channel = static_cast<int>(j);
        }
      }
      x = Phi * x + Gamma * u_previous + drive;
      u_previous = u;
    }
    figures.peak_share[static_cast<std::size_t>(forcing)] = peak;
    figures.peak_channel[static_cast<std::size_t>(forcing)] = channel;
  }
  return figures;
}

// The envelope's trims with the model's own rotor-speed model; `skipped` counts those it has none
// at (only the governor's: high speed, docs/model.md §11 ), which no controller of this model flies.
std::vector<Point> envelope_points(const Helicopter& model, const LqrScheduleGrid& grid, int& skipped) {
  std::vector<Point> points;
  skipped = 0;
  TrimGridAxes axes{grid.speeds, grid.courses, grid.climb_rates, kHoverAltitude};
  sweep_trims(model, axes, [&](std::size_t i, std::size_t j, std::size_t k, const GridTrim& found) {
    if (grid.speeds[i] == 0.0 && j > 0) return;  // one hover per climb rate
    if (&found.plant != &model) {
      ++skipped;
      return;
    }
    char label[120];
    std::snprintf(label, sizeof label, "speed %g m/s, course %g deg, climb %g m/s", grid.speeds[i],
                  grid.courses[j] * 180.0 / std::numbers::pi, grid.climb_rates[k]);
    points.push_back({label, lqr_linearization_state(found.trim.state), found.trim.input});
  });
  return points;
}

struct Accumulated {
  WeightCheck check;
  std::array<double, kForcings> peak_share{};  // over the points where the loop is stable
  bool fast_trouble = false;                   // unstable through a fast mode, or short of margin
  std::vector<std::string> slow_unstable;      // the points unstable through a slow mode
};

void record(Accumulated& into, const LoopFigures& figures, const std::string& point, double min_disk_margin) {
  WeightCheck& c = into.check;
  if (figures.slow_unstable) into.slow_unstable.push_back(point);
  else if (figures.spectral_radius >= 1.0 || figures.disk_margin < min_disk_margin) into.fast_trouble = true;
  if (figures.spectral_radius > c.spectral_radius) {
    c.spectral_radius = figures.spectral_radius;
    c.worst_point = point;
  }
  c.disk_margin = c.disk_margin == 0.0 ? figures.disk_margin : std::min(c.disk_margin, figures.disk_margin);
  for (int f = 0; f < kForcings; ++f) {
    const auto s = static_cast<std::size_t>(f);
    if (figures.spectral_radius < 1.0) into.peak_share[s] = std::max(into.peak_share[s], figures.peak_share[s]);
    if (figures.peak_share[s] > c.peak_input_share) {
      c.peak_input_share = figures.peak_share[s];
      c.peak_input = std::string(kChannels[figures.peak_channel[s]]) + ", " + kForcingNames[f] + " at " + point;
    }
  }
}

Eigen::VectorXd bryson_state_weights(const WeightDesignInputs& in) {
  const auto weight = [](double excursion) {
    if (!(excursion > 0.0) || !std::isfinite(excursion))
      throw Error("weights: every allowed excursion must be positive and finite");
    return 1.0 / (excursion * excursion);
  };
  Eigen::VectorXd q(kStateDim);
  q.segment<3>(kXp).setConstant(weight(in.position));
  q.segment<3>(kU).setConstant(weight(in.velocity));
  q[kPhi] = q[kTheta] = weight(in.attitude);
  q[kPsi] = weight(in.heading);
  q.segment<3>(kP).setConstant(weight(in.rate));
  q.segment<2>(kA1).setConstant(weight(in.flapping));
  q.segment<3>(kXi).setConstant(weight(in.integral));
  q[kS] = 0.0;
  return q;
}

}  // namespace

WeightDesign design_weights(const Helicopter& model, const WeightDesignInputs& inputs) {
  if (!(inputs.headroom_share > 0.0 && inputs.headroom_share <= 1.0))
    throw Error("weights: headroom_share must be in (0, 1]");
  inputs.envelope.validate();
  WeightDesign design;
  design.inputs = inputs;
  const Trim hover = find_trim(model, TrimCondition::hover(kHoverAltitude));
  const sim::ActuatorLimits limits = sim::ActuatorLimits::x_cell(model.parameters());
  design.headroom = (hover.input - limits.lower).cwiseMin(limits.upper - hover.input);
  design.state_weights = bryson_state_weights(inputs);
  design.input_weights = design.headroom.cwiseAbs2().cwiseInverse();
  const std::vector<Point> points = envelope_points(model, inputs.envelope, design.skipped_points);
  const OperatingPoint hover_point = operating_point(model, hover);

  for (design.adjustments = 0;; ++design.adjustments) {
    const Eigen::MatrixXd Q = design.state_weights.asDiagonal(), R = design.input_weights.asDiagonal();
    const Eigen::MatrixXd Q17 = Q.topLeftCorner(kDesignStates, kDesignStates);
    const Eigen::MatrixXd R_inverse = design.input_weights.cwiseInverse().asDiagonal();
    const Eigen::MatrixXd hover_gain = design_lqr(model, hover_point, Q, R, kDesignStates).K;
    ThetaDSettings theta_d_settings;
    theta_d_settings.Q = Q;
    theta_d_settings.R = R;
    theta_d_settings.initial_input = hover.input;
    ThetaDController theta_d(model, theta_d_settings);
    theta_d.reset(hover.state, 0.0);  // frozen at the hover it takes off from

    const char* names[] = {"theta-d", "sdre", "lqr", "lqr-scheduled"};
    std::vector<Accumulated> accumulated(4 * inputs.periods.size());
    for (std::size_t c = 0; c < 4; ++c)
      for (std::size_t p = 0; p < inputs.periods.size(); ++p)
        accumulated[c * inputs.periods.size() + p].check = {names[c], inputs.periods[p], 0.0, 0.0, 0.0, {}, {}};
    for (const Point& point : points) {
      const Linearization jacobian = linearize(model, point.state, point.input);
      const Eigen::MatrixXd A = jacobian.A.topLeftCorner(kDesignStates, kDesignStates);
      const Eigen::MatrixXd B = jacobian.B.topRows(kDesignStates);
      const SdcPlant::Coefficients sdc = model.sdc(point.state, point.input);
      // Each controller's gain at the trim on the tracking vector without s: θ–D's series there
      // (higher terms fully faded in), the SDRE's P(x*), the hover gain, the trim's own LQR.
      const Eigen::MatrixXd gains[] = {
          (R_inverse * sdc.B.transpose() * theta_d.value_matrix(point.state, point.input, 1e9))
              .leftCols(kDesignStates),
          solve_care(sdc.F, sdc.B, Q, R).K.leftCols(kDesignStates), hover_gain, solve_care(A, B, Q17, R).K};
      for (std::size_t c = 0; c < 4; ++c)
        for (std::size_t p = 0; p < inputs.periods.size(); ++p)
          record(accumulated[c * inputs.periods.size() + p],
                 check_loop(A, B, gains[c], inputs.periods[p], design.headroom), point.label,
                 inputs.min_disk_margin);
    }
    design.checks.clear();
    std::array<bool, kForcings> exceeded{};
    bool fast_trouble = false;
    std::vector<std::string> slow_unstable;
    for (const Accumulated& a : accumulated) {
      design.checks.push_back(a.check);
      fast_trouble = fast_trouble || a.fast_trouble;
      for (const std::string& point : a.slow_unstable)
        slow_unstable.push_back(a.check.controller + " at " + std::to_string(1.0 / a.check.period).substr(0, 4) +
                                " Hz, " + point);
      for (int f = 0; f < kForcings; ++f)
        if (a.peak_share[static_cast<std::size_t>(f)] > inputs.headroom_share) exceeded[static_cast<std::size_t>(f)] = true;
    }
    const bool any_exceeded = std::any_of(exceeded.begin(), exceeded.end(), [](bool e) { return e; });
    design.holds = !fast_trouble && !any_exceeded && slow_unstable.empty();
    // What no adjustment fixes: a loop unstable through a slow mode (the controller's gain there
    // does not hold the mode, whatever the bandwidth). Reported; the rest is still adjusted.
    if ((!fast_trouble && !any_exceeded) || design.adjustments == inputs.max_adjustments) {
      design.unmet.clear();
      for (const std::string& where : slow_unstable)
        design.unmet.push_back("unstable through a slow mode (no weights of this design fix it): " + where);
      if (fast_trouble)
        design.unmet.push_back("a controller's sampled loop is unstable through a fast mode, or its disk margin below " +
                               std::to_string(inputs.min_disk_margin) + ", somewhere in the envelope");
      for (int f = 0; f < kForcings; ++f)
        if (exceeded[static_cast<std::size_t>(f)])
          design.unmet.push_back(std::string("the input peak of the ") + kForcingNames[f] + " exceeds " +
                                 std::to_string(inputs.headroom_share) + " of the headroom");
      return design;
    }
    // A deterministic step: a sampled loop unstable through a fast mode or short of margin
    // doubles R (every loop slower, the fast ones, which one sample of delay at 100 Hz cannot
    // hold, first); otherwise a response that asks for too much input halves the weights that
    // drive it.
    if (fast_trouble) {
      design.input_weights *= 2.0;
    } else {
      for (int f = 0; f < kForcings; ++f)
        if (exceeded[static_cast<std::size_t>(f)])
          for (const int entry : weights_of(f)) design.state_weights[entry] *= 0.5;
    }
  }
}

std::string weights_settings_text(const WeightDesign& design) {
  std::ostringstream text;
  text.precision(6);
  const WeightDesignInputs& in = design.inputs;
  text << "# Weights designed by `thetad weights` (docs/weights.md): Bryson's rule on the allowed excursions\n"
       << "# position " << in.position << " m, velocity " << in.velocity << " m/s, attitude " << in.attitude
       << " rad, heading " << in.heading << " rad, rates " << in.rate << " rad/s, flapping " << in.flapping
       << " rad, integrals " << in.integral << " m s\n"
       << "# and the input headroom from hover (T_mr, delta_ped, delta_col, delta_lon, delta_lat): "
       << design.headroom.transpose() << "\n"
       << "# then " << design.adjustments << " adjustment(s) until every controller's linearized loop, sampled at";
  for (const double period : in.periods) text << " " << 1.0 / period << " Hz";
  const auto values = [&text](const std::vector<double>& list, double scale) {
    for (std::size_t i = 0; i < list.size(); ++i) text << (i ? " " : "") << list[i] * scale;
  };
  text << " with one sample of delay,\n# is stable at every trim of the envelope (--speeds ";
  values(in.envelope.speeds, 1.0);
  text << " --courses-deg ";
  values(in.envelope.courses, 180.0 / std::numbers::pi);
  text << " --climb-rates ";
  values(in.envelope.climb_rates, 1.0);
  text << ":\n# " << in.envelope.speeds.size()
       << " speeds x " << in.envelope.courses.size() << " courses x " << in.envelope.climb_rates.size()
       << " climb rates; " << design.skipped_points
       << " point(s) without a trim of the model's rotor-speed model not checked) and the responses to 1 m steps and 1 m/s^2 stay within " << in.headroom_share
       << " of the headroom: " << (design.holds ? "they hold." : "NOT MET.") << "\n";
  for (const std::string& unmet : design.unmet) text << "# not met: " << unmet << "\n";
  for (const WeightCheck& c : design.checks) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "# %-13s %6.0f Hz: spectral radius %.6f (worst at %s), disk margin >= %.3f, peak input %.2f of the "
                  "headroom (%s)\n",
                  c.controller.c_str(), 1.0 / c.period, c.spectral_radius, c.worst_point.c_str(), c.disk_margin,
                  c.peak_input_share, c.peak_input.c_str());
    text << line;
  }
  const auto list = [&text](const Eigen::VectorXd& v) {
    text << "[";
    for (Eigen::Index i = 0; i < v.size(); ++i) text << (i ? ", " : "") << v[i];
    text << "]";
  };
  for (const char* controller : {"theta-d", "sdre", "lqr", "lqr-scheduled"}) {
    text << controller << ":\n  Q: ";
    list(design.state_weights);
    text << "\n  R: ";
    list(design.input_weights);
    text << "\n";
  }
  return text.str();
}

}  // namespace thetad
