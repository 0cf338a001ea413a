// The θ–D step off the pattern reset() probed: a plant whose coefficients near x0 vary in a few
// entries and whose B is zero outside 8 of 18 rows, but which far from x0 grows new coefficients
// in F, or a nonzero of B outside those rows, or both. control() must then leave its shortcuts
// (the T1 basis, the products on the input rows only, the last term on those rows) for that pass
// and still give the u of the written-out series, on the helicopter's fixed sizes and on dynamic
// ones. The plant's A is block triangular, as the helicopter's closed loop is reducible, so that
// the Lyapunov inverse has exact zeros and the step's blocks and supports (ZeroPatternProduct,
// the projections on their supports) are exercised too.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "controllers/theta_d.hpp"
#include "core/sdc_plant.hpp"
#include "tests/controllers/theta_d_reference_law.hpp"
#include "tests/heap_counter.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr int kStates = 18, kInputs = 5, kFirstInputRow = 10;

// F(x; u) = A + x0 C + tanh(u0) H + d(x2) E,  B(x) = G + x1 K + d(x3) e0 e2ᵀ,  d(s) = max(0, |s| − 1)²:
// G and K live in rows 10 … 17 only, C, H and E are sparse with disjoint patterns, and d vanishes
// within |s| ≤ 1, where reset() probes (x0 = 0). A has no entry from states 10 … 17 into rows
// 0 … 9, whose own block is stable (they are not controllable: the CARE needs them stable).
class LatePatternPlant final : public SdcPlant {
 public:
  LatePatternPlant() : A_(kStates, kStates), C_(MatrixXd::Zero(kStates, kStates)), H_(C_), E_(C_),
                       G_(MatrixXd::Zero(kStates, kInputs)), K_(G_) {
    std::mt19937_64 generator(5);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (Eigen::Index j = 0; j < A_.size(); ++j) A_.data()[j] = normal(generator) / std::sqrt(double(kStates));
    A_.topRightCorner(kFirstInputRow, kStates - kFirstInputRow).setZero();
    A_.topLeftCorner(kFirstInputRow, kFirstInputRow).diagonal().array() -= 2.0;
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
    F = A_ + x[0] * C_ + std::tanh(u[0]) * H_ + late(x[2]) * E_;
    B = G_ + x[1] * K_;
    B(0, 2) = late(x[3]);
  }

 private:
  static double late(double s) { return std::pow(std::max(0.0, std::abs(s) - 1.0), 2); }

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
  // States on the probed pattern and off it in F only (|x2| > 1), in B only (|x3| > 1) and in
  // both, in turn, so that steps leave and rejoin the shortcuts with T1 carried over between them.
  std::vector<VectorXd> states;
  for (int k = 0; k < 12; ++k) {
    VectorXd x = VectorXd::LinSpaced(kStates, -0.2, 0.3) * (1.0 + 0.1 * k);
    x[2] = k % 4 == 1 || k % 4 == 3 ? 1.3 + 0.1 * k : 0.4;
    x[3] = k % 4 >= 2 ? -1.2 - 0.1 * k : -0.3;
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
            << "state " << k << " (" << (k % 4 == 0 ? "on the pattern" : k % 4 == 1 ? "F off it" : k % 4 == 2 ? "B off it" : "both off it")
            << "), " << passes << " passes, " << (fixed_size ? "fixed" : "dynamic") << " size";
        previous = u;
      }
    }
}

TEST(ThetaDOffThePattern, ControlAllocatesNothingOnAndOffThePattern) {
  const LatePatternPlant plant;
  VectorXd on = VectorXd::Constant(kStates, 0.1), off = on;
  off[2] = 1.5;
  off[3] = -1.4;
  VectorXd u(kInputs);
  const Reference reference;
  for (const int passes : {1, 3}) {  // the blocks of the last term; the projections
    ThetaDController controller(plant, every_pass(passes, true));
    controller.reset(VectorXd::Zero(kStates), 0.0);
    controller.control(0.0, on, reference, u);
    const long allocations = testing::heap_allocations_during([&] {
      controller.control(0.01, on, reference, u);
      controller.control(0.02, off, reference, u);
    });
    if (allocations < 0) GTEST_SKIP() << "malloc cannot be interposed in this build (AddressSanitizer)";
    EXPECT_EQ(allocations, 0) << passes << " passes";
  }
}

TEST(ThetaDOffThePattern, TheValueMatrixEqualsTheWrittenOutSeriesOffThePattern) {
  const LatePatternPlant plant;
  for (const bool fixed_size : {true, false}) {
    ThetaDController controller(plant, every_pass(1, fixed_size));
    controller.reset(VectorXd::Zero(kStates), 0.0);
    VectorXd x = VectorXd::Constant(kStates, 0.1);
    x[2] = -1.6;
    x[3] = 1.7;
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
