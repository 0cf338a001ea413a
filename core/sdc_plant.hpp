#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/control_law.hpp"
#include "core/feedforward.hpp"
#include "core/log_column.hpp"

namespace thetad {

// A state entry that the reference's position commands: the helicopter's x_p is commanded by
// x_c, the first entry of Reference::position.
struct TrackedState {
  int index = 0;      // into the state
  std::string axis;   // what results call its error ("x")
  LogColumn command;  // the commanded value's log column ("x_c", "m")
};

// What a controller designed for this plant starts from where its settings say nothing.
struct DesignDefaults {
  Eigen::VectorXd state_weights;  // diagonal of Q (n)
  Eigen::VectorXd input_weights;  // diagonal of R (m)
  Eigen::VectorXd input;          // u0: where the first SDC is taken and the fixed point starts (m)
};

// A plant in state-dependent-coefficient (SDC) form: xdot = f(x, u) = F(x) x + B(x) u, exactly.
//
// F and B may also depend on the input through quantities the plant derives from it (the
// helicopter's rotor speed follows from the commanded thrust), so sdc() takes the input at which
// those are evaluated: F(x; u) x + B(x; u) u == f(x, u) holds for that u. A plant whose
// coefficients do not depend on u ignores it. Controllers that need the exact identity iterate
// u -> sdc(x, u) -> u' to a fixed point.
//
// The writing overloads are the hot path: they fill caller-provided storage and allocate nothing.
class SdcPlant {
 public:
  virtual ~SdcPlant() = default;

  virtual int state_dim() const = 0;
  virtual int input_dim() const = 0;

  virtual void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                 Eigen::Ref<Eigen::VectorXd> xdot) const = 0;

  // The Jacobians of f at (x, u), dfdx (n x n) and dfdu (n x m), exact (by hand or by automatic
  // differentiation) for a plant that has them: the optimal control transcription needs them. A
  // plant without returns false (the default) and writes nothing.
  virtual bool jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                        Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const {
    (void)x;
    (void)u;
    (void)dfdx;
    (void)dfdu;
    return false;
  }

  // Whether F and B change with the input (then sdc(x, u) needs the input being computed, and a
  // controller iterates to the fixed point; otherwise one evaluation is exact).
  virtual bool sdc_depends_on_input() const { return false; }

  // The vector a controller's value function acts on, built from the measured state and the
  // reference: the state itself for a regulator (the default), V_track of Eq. (36) for the
  // helicopter's position servo. Writes all n entries.
  virtual void tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference,
                               Eigen::Ref<Eigen::VectorXd> v) const {
    (void)reference;
    v = measured;
  }

  // The tracking vector on the plant's true state, for a run's cost: `error_integral` is the
  // integral of the true tracking error of tracked_states() (PositionIntegral rule, zeros beyond
  // them). The default is tracking_vector() of the true state.
  virtual void true_tracking_vector(const Eigen::Ref<const Eigen::VectorXd>& x, const Reference& reference,
                                    const Eigen::Vector3d& error_integral, Eigen::Ref<Eigen::VectorXd> v) const {
    (void)error_integral;
    tracking_vector(x, reference, v);
  }

  // The states that Reference::position commands, in its order (at most three): a run's tracking
  // error is x[index] minus the command. None (the default) for a regulator.
  virtual std::vector<TrackedState> tracked_states() const { return {}; }

  // Feed-forward (docs/model.md §7.1). The state that is constant 1 in the tracking vector (the
  // helicopter's bias state s): the error form puts the reference and trim terms in its column of
  // F. -1 (the default): the plant has none, and its controllers fly feedforward none only.
  virtual int bias_state() const { return -1; }

  // Overwrites in motion.state the entries that the reference commands at this sample: the
  // tracked positions, their integrals and the plant's velocity states (in the plant's own frame,
  // which may be the measured attitude's: hence `measured`), and in motion.rate their exact time
  // derivatives along the reference and that frame. Leaves every other entry of both, and the
  // input, as they are. Allocates nothing. The default commands nothing (a regulator).
  virtual void commanded_motion(const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference,
                                TrimPoint& motion) const {
    (void)measured;
    (void)reference;
    (void)motion;
  }

  // The plant's trims along `reference`, for the `period` samples of `duration` s, designed now
  // (the helicopter: a table of Ipopt trims over the velocities the reference commands). Null (the
  // default): the plant has no trims, and no controller flies velocity+trim on it. Throws
  // thetad::Error naming the time and the command where the reference leaves the plant's trims.
  virtual std::shared_ptr<const TrimSource> trim_source(const ReferenceTrajectory& reference, double duration,
                                                        double period) const {
    (void)reference;
    (void)duration;
    (void)period;
    return nullptr;
  }

  // The tracked states' values in x, in Reference::position's order (zeros beyond them): the
  // command that holds the plant where it is.
  Eigen::Vector3d tracked_position(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    const std::vector<TrackedState> tracked = tracked_states();
    for (std::size_t i = 0; i < tracked.size(); ++i) position[static_cast<Eigen::Index>(i)] = x[tracked[i].index];
    return position;
  }

  // Names and units of the states and inputs in index order, for logs, plots and Python; the
  // defaults are x_0, x_1, ... and u_0, u_1, ... without units.
  virtual std::vector<LogColumn> state_columns() const { return numbered_columns("x_", state_dim()); }
  virtual std::vector<LogColumn> input_columns() const { return numbered_columns("u_", input_dim()); }

  // The plant knows what a sensible design starts from (the helicopter: the paper's weights and
  // hover thrust); a plant that does not say weighs every state and input alike around u0 = 0.
  virtual DesignDefaults design_defaults() const {
    return {Eigen::VectorXd::Ones(state_dim()), Eigen::VectorXd::Ones(input_dim()), Eigen::VectorXd::Zero(input_dim())};
  }

  // Writes every entry of F (n x n) and B (n x m), zeros included.
  virtual void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                   Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const = 0;

  // sdc() in two parts, for a caller that evaluates F and B into the same buffers at every step:
  // sdc_constant() once, then sdc_varying() per evaluation, which may leave the entries that
  // sdc_constant() wrote (zeros and entries that depend on neither x nor u) as they are. The
  // defaults write nothing once and everything each time, so a plant need not know about them.
  virtual void sdc_constant(Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
    (void)F;
    (void)B;
  }
  virtual void sdc_varying(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
    sdc(x, u, F, B);
  }

  Eigen::VectorXd f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u) const {
    Eigen::VectorXd xdot(state_dim());
    f(x, u, xdot);
    return xdot;
  }

  struct Coefficients {
    Eigen::MatrixXd F;
    Eigen::MatrixXd B;
  };
  Coefficients sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u) const {
    Coefficients c{Eigen::MatrixXd(state_dim(), state_dim()), Eigen::MatrixXd(state_dim(), input_dim())};
    sdc(x, u, c.F, c.B);
    return c;
  }

 private:
  static std::vector<LogColumn> numbered_columns(const std::string& prefix, int count) {
    std::vector<LogColumn> columns;
    for (int i = 0; i < count; ++i) columns.push_back({prefix + std::to_string(i), ""});
    return columns;
  }
};

}  // namespace thetad
