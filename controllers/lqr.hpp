#pragma once

// A single-point LQR baseline: u = u* − K (V − V*), with K from one CARE on the linearization of
// the model at an operating point (x*, u*) and V = model.tracking_vector(measured, reference).
// For the helicopter the operating point is the hover trim and V is V_track (Eq. 36): the same
// servo structure (position, velocity, attitude, rate, flapping and integral errors) and the same
// Q and R (§7.2) as θ–D and the SDRE, but a gain fixed once, so it shows what their
// state dependence buys away from hover.
//
// Why the trim and not xa(t0) as θ–D does (docs/model.md §8.1): xa(t0) is on the ground at rest, not an
// equilibrium (the tail-rotor force is unbalanced at φ = 0), so u* would be meaningless there; the
// hover trim is the point the helicopter is asked to hold. The trim of this model does not depend
// on altitude, so the hover trim at the initial state's altitude and heading is the hover trim at
// the reference's altitude too.

#include <memory>
#include <string>

#include <Eigen/Core>

#include "controllers/controller.hpp"
#include "controllers/linearization.hpp"
#include "core/sdc_plant.hpp"

namespace thetad {

struct LqrSettings {
  // Q n×n symmetric positive semi-definite, R m×m symmetric positive definite; only the top-left
  // design_states block of Q is used.
  Eigen::MatrixXd Q;
  Eigen::MatrixXd R;
  // The first design_states states enter the design (the helicopter: 17, without the bias state
  // s, which is constant). 0: all.
  Eigen::Index design_states = 0;
};

class LqrController final : public NamedController<"lqr"> {
 public:
  // Designs the gain now (one CARE): reset() and clones reuse it. Keeps a reference to the model:
  // it must outlive the controller and its clones. Throws thetad::Error on settings that do not
  // fit the model or when the CARE has no stabilizing solution.
  LqrController(const SdcPlant& model, OperatingPoint point, LqrSettings settings);
  // With a gain designed elsewhere (K of `design`, on the first design_states states): the
  // feed-forward LQR flies on the error form a gain designed on the plant at its trim.
  LqrController(const SdcPlant& model, OperatingPoint point, CareResult design, Eigen::Index design_states);

  std::unique_ptr<Controller> clone() const override { return std::make_unique<LqrController>(*this); }

  void reset(const Eigen::VectorXd& x0, double t0) override;
  // u = u* − K (V − V*). Allocates nothing.
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;

  const OperatingPoint& operating_point() const { return point_; }
  // K, P and the closed-loop eigenvalues of the design (on the design states).
  const CareResult& design() const { return design_; }

 private:
  const SdcPlant* model_;
  OperatingPoint point_;
  CareResult design_;
  Eigen::Index design_states_;
  Eigen::VectorXd v_;  // V, then V − V* on the design states
};

}  // namespace thetad
