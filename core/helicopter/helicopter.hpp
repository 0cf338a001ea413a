#pragma once

#include <Eigen/Core>

#include "core/helicopter/model_options.hpp"
#include "core/helicopter/parameters.hpp"
#include "core/helicopter/state.hpp"
#include "core/sdc_plant.hpp"

namespace thetad::heli {

// What the air and the rotor wake do during one sample (held between samples by the simulator).
// The controller's model uses the default: no wind, nominal induced velocities.
struct Environment {
  Eigen::Vector3d wind_ned = Eigen::Vector3d::Zero();         // inertial wind W_N, W_E, W_D (m/s)
  Eigen::Vector3d wind_body_scale = Eigen::Vector3d::Ones();  // Table 1 #26-28 on u_w, v_w, w_w
  double induced_main_scale = 1.0;                            // Table 1 #29 on V_imr
  double induced_tail_scale = 1.0;                            // Table 1 #30 on V_itr
};

// The X-Cell 60 of the paper over the 18-state augmented vector (docs/model.md §2, §6):
// f(x, u) is Eqs. 1-9 and 26 with Appendix A and B; sdc(x, u) is Eqs. 29-30 with the rotor speed
// taken from u's thrust, so F x + B u == f(x, u) exactly.
class Helicopter final : public SdcPlant {
 public:
  explicit Helicopter(const Parameters& parameters = Parameters::nominal(),
                      const ModelOptions& options = ModelOptions::resolved());

  int state_dim() const override { return kStateDim; }
  int input_dim() const override { return kInputDim; }

  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override;
  // df/dx and df/du by forward automatic differentiation of f's own code (Eigen's AutoDiff), the
  // rotor speed by the implicit-function theorem: exact to rounding wherever f is smooth.
  bool jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const override;
  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;
  // sdc() in two parts: the zeros and the 15 entries set by the parameters alone, and the other
  // 45 of the 414 (those that depend on x or, through the rotor speed, on u).
  void sdc_constant(Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;
  void sdc_varying(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                   Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;

  // The rotor speed follows T_mr, except with the governor model.
  bool sdc_depends_on_input() const override {
    return options_.rotor_speed_model != ModelOptions::RotorSpeedModel::governor;
  }
  // V_track of Eq. (36) (docs/model.md §7).
  void tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference,
                       Eigen::Ref<Eigen::VectorXd> v) const override;
  // V_track on the true state: its integral entries are the integral of the true position error,
  // by the rule the controller's measured integral follows, not the true state's own x_i.
  void true_tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& x, const Reference& reference,
                            const Eigen::Vector3d& error_integral, Eigen::Ref<Eigen::VectorXd> v) const override;
  // x_p, y_p, z_p, commanded by x_c, y_c, z_c (m).
  std::vector<TrackedState> tracked_states() const override;
  // Feed-forward (docs/model.md §7.1): the bias state s, the commanded position, body velocity (in
  // the measured attitude's frame) and integrals, and the trim table (core/trim_table.hpp).
  int bias_state() const override { return kS; }
  void commanded_motion(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference,
                        TrimPoint& motion) const override;
  std::shared_ptr<const TrimSource> trim_source(const ReferenceTrajectory& reference, double duration,
                                                double period) const override;
  // The 18 states and 5 inputs by their names in docs/model.md §1 (x_p ... s; T_mr ... delta_lat).
  std::vector<LogColumn> state_columns() const override;
  std::vector<LogColumn> input_columns() const override;

  // The paper's weights (Eqs. 33-34, paper_weights.hpp) and u0 = [m g, 0, 0, 0, 0], the rotor at
  // hover thrust (docs/model.md §8.1, §6.2).
  DesignDefaults design_defaults() const override;

  // F and B at a given main-rotor speed (what the controller's fixed point of docs/model.md §6.2 iterates on).
  void sdc_at_rotor_speed(const Eigen::Ref<const Eigen::VectorXd>& x, double rotor_speed,
                          Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const;

  // Omega_mr for thrust T_mr at state x (Eqs. A4-A6 by bracketed zero-finding, or Omega_nom with
  // the governor model). Throws thetad::Error when no root exists.
  double rotor_speed(const Eigen::Ref<const Eigen::VectorXd>& x, double thrust) const;

  const Parameters& parameters() const { return parameters_; }
  const ModelOptions& options() const { return options_; }
  const Environment& environment() const { return environment_; }
  void set_environment(const Environment& environment) { environment_ = environment; }

 private:
  Parameters parameters_;
  ModelOptions options_;
  Environment environment_;
};

}  // namespace thetad::heli
