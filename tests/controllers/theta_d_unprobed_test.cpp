// The θ–D step off the pattern reset() probed: a plant whose coefficients near x0 vary in a few
// entries and whose B is zero outside 8 of 18 rows, but which far from x0 grows new coefficients
// in F and a nonzero of B outside those rows. control() must then leave its shortcuts (the T1
// basis, the products on the input rows only, the last term on those rows) for that pass and
// still give the u of the written-out series, on the helicopter's fixed sizes and on dynamic ones.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "controllers/theta_d.hpp"
#include "core/sdc_plant.hpp"
#include "tests/controllers/theta_d_reference_law.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr int kStates = 18, kInputs = 5, kFirstInputRow = 10;

// F(x; u) = A + x0 C + tanh(u0) H + d(x) E,  B(x) = G + x1 K + d(x) e0 e2ᵀ,  d(x) = max(0, |x2| − 1)²:
// G and K live in rows 10 … 17 only, C, H and E are sparse with disjoint patterns, and d vanishes
// within |x2| ≤ 1, where reset() probes (x0 = 0).
class LatePatternPlant final : public SdcPlant {
 public:
  LatePatternPlant() : A_(kStates, kStates), C_(MatrixXd::Zero(kStates, kStates)), H_(C_), E_(C_),
                       G_(MatrixXd::Zero(kStates, kInputs)), K_(G_) {
    std::mt19937_64 generator(5);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (Eigen::Index j = 0; j < A_.size(); ++j) A_.data()[j] = normal(generator) / std::sqrt(double(kStates));
    for (Eigen::Index r = kFirstInputRow; r < kStates; ++r)
      for (Eigen::Index c = 0; c < kInputs; ++c) G_(r, c) = normal(generator);
    for (int k = 0; k < 6; ++k) {
      C_(k, (5 * k + 3) % kStates) = 0.3 * normal(generator);
      H_(k + 6, (7 * k + 1) % kStates) = 0.3 * normal(generator);
      E_(k + 12, (3 * k + 2) % kStates) = 0.5 * normal(generator);
      K_(kFirstInputRow + k, k % kInputs) = 0.3 * normal(generator);
    }
  }

  int state_dim() const override { return kStates; }
  int input_dim() const override { return kInputs; }
  bool sdc_depends_on_input() const override { return true; }

  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const VectorXd>& x, const Eigen::Ref<const VectorXd>& u, Eigen::Ref<VectorXd> xdot) const override {
    MatrixXd F(kStates, kStates), B(kStates, kInputs);
    sdc(x, u, F, B);
    xdot.noalias() = F * x + B * u;
  }
  void sdc(const Eigen::Ref<const VectorXd>& x, const Eigen::Ref<const VectorXd>& u, Eigen::Ref<MatrixXd> F,
           Eigen::Ref<MatrixXd> B) const override {
    const double late = std::pow(std::max(0.0, std::abs(x[2]) - 1.0), 2);
    F = A_ + x[0] * C_ + std::tanh(u[0]) * H_ + late * E_;
    B = G_ + x[1] * K_;
    B(0, 2) = late;
  }

 private:
  MatrixXd A_, C_, H_, E_, G_, K_;
};

ThetaDSettings every_pass(int passes, bool fixed_size) {
  ThetaDSettings s;
  s.Q = MatrixXd::Identity(kStates, kStates);
  s.R = VectorXd::LinSpaced(kInputs, 1.0, 2.0).asDiagonal();
  s.fixed_point_iterations = passes;
  s.fixed_point_tolerance = 0.0;
  s.fixed_size = fixed_size;
  return s;
}

TEST(ThetaDOffThePattern, ControlEqualsTheWrittenOutSeriesOnAndOffThePattern) {
  const LatePatternPlant plant;
  // Alternating states on the probed pattern (|x2| < 1) and off it (|x2| > 1), so that passes leave
  // and rejoin the shortcuts, with T1 carried over between passes and steps.
  std::vector<VectorXd> states;
  for (int k = 0; k < 8; ++k) {
    VectorXd x = VectorXd::LinSpaced(kStates, -0.2, 0.3) * (1.0 + 0.1 * k);
    x[2] = k % 2 == 0 ? 0.4 : 1.3 + 0.1 * k;
    states.push_back(x);
  }
  const Reference reference;
  for (const bool fixed_size : {true, false})
    for (const int passes : {1, 3}) {
      ThetaDController controller(plant, every_pass(passes, fixed_size));
      controller.reset(VectorXd::Zero(kStates), 0.0);
      VectorXd u(kInputs), v(kStates), previous = controller.settings().initial_input;
      for (std::size_t k = 0; k < states.size(); ++k) {
        const double t = 0.01 * double(k);
        controller.control(t, states[k], reference, u);
        plant.tracking_vector(states[k], reference, v);
        const VectorXd expected = testing::reference_control(controller, plant, states[k], previous, v, t, passes);
        EXPECT_LE((u - expected).norm(), 1e-12 * expected.norm())
            << "state " << k << (k % 2 == 0 ? " (on" : " (off") << " the pattern), " << passes << " passes, "
            << (fixed_size ? "fixed" : "dynamic") << " size";
        previous = u;
      }
    }
}

TEST(ThetaDOffThePattern, TheValueMatrixEqualsTheWrittenOutSeriesOffThePattern) {
  const LatePatternPlant plant;
  for (const bool fixed_size : {true, false}) {
    ThetaDController controller(plant, every_pass(1, fixed_size));
    controller.reset(VectorXd::Zero(kStates), 0.0);
    VectorXd x = VectorXd::Constant(kStates, 0.1);
    x[2] = -1.6;
    const VectorXd input = VectorXd::Constant(kInputs, 0.2);
    const double t = 0.7;
    const ThetaDSettings& s = controller.settings();
    const VectorXd e{{perturbation_factor(s.k[0], s.l[0], t), perturbation_factor(s.k[1], s.l[1], t)}};
    const MatrixXd expected = controller.series_expansion(x, input).evaluate(e);
    EXPECT_LE((controller.value_matrix(x, input, t) - expected).norm(), 1e-12 * expected.norm());
  }
}

}  // namespace
}  // namespace thetad
