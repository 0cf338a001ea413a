#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/controller_column.hpp"

namespace thetad {

// The position integrals of V_track (Eq. 36) are accumulated by one rule, on both sides of the
// loop (docs/model.md §7, §11, §10): left rectangles at the controller rate, starting at 0 at t0. At
// controller sample k the value is sum_{j<k} position(t_j) * T_c; the sample's own position is
// added after the control has been computed. The simulator uses it for the command integral and
// for the measured-position integral it reports in the measured state; a controller that keeps
// its own integral uses this type, so that a perfectly tracked reference leaves an integral
// error of exactly zero whatever the reference's shape.
struct PositionIntegral {
  Eigen::Vector3d value = Eigen::Vector3d::Zero();

  void accumulate(const Eigen::Vector3d& position, double controller_period) {
    value += position * controller_period;
  }
};

// What the controller is asked to track at one sample: the commanded inertial position (NED), its
// integral by the PositionIntegral rule (the "∫x_c dt" entries of Eq. 36), and the commanded
// velocity and acceleration, the position's exact time derivatives (right-continuous: at a phase
// boundary, the new phase's). A controller may use any of them; the paper's θ–D and SDRE use the
// position and its integral only.
struct Reference {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d integral = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      // m/s, NED
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  // m/s², NED
};

// A commanded position as a function of time. Only the position: the simulator integrates it with
// the PositionIntegral rule at the controller rate, because the integral must be accumulated
// exactly as the controller accumulates the measured position (docs/model.md §7, §10); a closed-form
// integral from the trajectory would differ from that rule by O(T_c) and show up as a spurious
// integral error that the integral gains (Q up to 1e6) act on.
class ReferenceTrajectory {
 public:
  virtual ~ReferenceTrajectory() = default;
  virtual Eigen::Vector3d position(double t) const = 0;
  // The exact first and second time derivatives of position(t), from the right where they jump
  // (a step's jump itself is not one: both are those of the motion after it).
  virtual Eigen::Vector3d velocity(double t) const = 0;
  virtual Eigen::Vector3d acceleration(double t) const = 0;
};

// Holds one point: hover tests and open-loop runs.
class FixedPosition final : public ReferenceTrajectory {
 public:
  explicit FixedPosition(const Eigen::Vector3d& position) : position_(position) {}
  Eigen::Vector3d position(double) const override { return position_; }
  Eigen::Vector3d velocity(double) const override { return Eigen::Vector3d::Zero(); }
  Eigen::Vector3d acceleration(double) const override { return Eigen::Vector3d::Zero(); }

 private:
  Eigen::Vector3d position_;
};

// What the simulator calls at every controller sample. control() is the hot path: it must not
// allocate; it writes every entry of u (input_dim of the plant). measured_state is the noisy
// 18-vector of the plant's augmented state (see measure() in core/sim/noise.hpp for what each
// entry holds). Numerical failures throw thetad::Error; the simulator records them as the end of
// the run.
class ControlLaw {
 public:
  virtual ~ControlLaw() = default;
  virtual std::string name() const = 0;
  // Called once before the first sample with the initial (true, noise-free) state.
  virtual void reset(const Eigen::VectorXd& x0, double t0) = 0;
  virtual void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                       const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) = 0;

  // Named event counts since the last reset() that the run summary reports next to the tracking
  // figures, e.g. the SDRE's CARE failures that fell back to the last good solution. A law that
  // has nothing to report keeps this default (none).
  virtual std::vector<std::pair<std::string, double>> counters() const { return {}; }

  // Columns the law writes into the run log at every sample: numbers of its own state or work, and
  // certificates of its own answer (docs/model.md §8.4), which the run also summarizes by their
  // worst value. log_columns() is fixed from construction on; log_values() appends the last
  // control()'s values to `row` in that order. log_values() is on the hot path: `row` has the
  // capacity, nothing may allocate. A law that writes none keeps these defaults.
  virtual std::vector<ControllerColumn> log_columns() const { return {}; }
  virtual void log_values(std::vector<double>& row) const { (void)row; }

  // The iterations the last control() took (θ–D's and the SDRE's fixed-point passes): the work a
  // step did, which `thetad bench` reports beside its time. A closed-form law keeps 0. Hot path: a
  // plain read.
  virtual int last_iterations() const { return 0; }
};

// Applies a fixed input whatever the state: open-loop runs and tests.
class ConstantInput final : public ControlLaw {
 public:
  explicit ConstantInput(Eigen::VectorXd u, std::string name = "constant_input")
      : u_(std::move(u)), name_(std::move(name)) {}

  std::string name() const override { return name_; }
  void reset(const Eigen::VectorXd&, double) override {}
  void control(double, const Eigen::Ref<const Eigen::VectorXd>&, const Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u = u_;
  }

 private:
  Eigen::VectorXd u_;
  std::string name_;
};

}  // namespace thetad
