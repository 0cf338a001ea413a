#pragma once

// What a controller saw and answered at each sample of a closed-loop run, for the programs that
// replay those samples to another controller: the per-step benchmarks and the allocation test.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/control_law.hpp"

namespace thetad::sim {

struct ControlSample {
  double t;
  Eigen::VectorXd state;  // measured (noisy)
  Reference reference;
  Eigen::VectorXd input;  // what the recorded law commanded
};

// Passes every call on to the law it wraps and keeps the samples from time `from` on. Records, so
// it allocates: a harness, never flown in a measured run.
class RecordingLaw final : public ControlLaw {
 public:
  RecordingLaw(ControlLaw& inner, double from, std::vector<ControlSample>& samples)
      : inner_(inner), from_(from), samples_(samples) {}
  std::string name() const override { return inner_.name(); }
  void reset(const Eigen::VectorXd& x0, double t0) override { inner_.reset(x0, t0); }
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override {
    inner_.control(t, measured, reference, u);
    if (t >= from_) samples_.push_back({t, measured, reference, u});
  }

 private:
  ControlLaw& inner_;
  double from_;
  std::vector<ControlSample>& samples_;
};

}  // namespace thetad::sim
