#include <cstdint>
#include <vector>

#include <Eigen/Cholesky>

#include "core/error.hpp"
#include "core/lyapunov.hpp"
#include "export/design_export.hpp"
#include "export/onboard/helicopter_sdc.hpp"

namespace thetad {

namespace {

// The unknowns T(i, j), i ≤ j, of a symmetric term: those in a row where B can be nonzero first
// (the last term is solved for them only), each part in packed order (ThetaDController's
// order_unknowns, before its grouping by zero pattern).
struct Unknowns {
  std::vector<int> row, col;
  int input_row_count = 0;
};

Unknowns order_unknowns() {
  bool input_row[thetad_onboard::kStates] = {};
  for (const int r : thetad_onboard::kInputRows) input_row[r] = true;
  Unknowns unknowns;
  for (const bool in_input_rows : {true, false}) {
    for (int j = 0; j < thetad_onboard::kStates; ++j)
      for (int i = 0; i <= j; ++i) {
        if ((input_row[i] || input_row[j]) != in_input_rows) continue;
        unknowns.row.push_back(i);
        unknowns.col.push_back(j);
      }
    if (in_input_rows) unknowns.input_row_count = static_cast<int>(unknowns.row.size());
  }
  return unknowns;
}

}  // namespace

ExportedDesign theta_d_design(const ThetaDController& controller, bool feedforward_velocity) {
  const ThetaDSettings& settings = controller.settings();
  const Eigen::MatrixXd& A0 = controller.A0();
  if (A0.rows() != thetad_onboard::kStates || controller.g0().cols() != thetad_onboard::kInputs)
    throw Error("export: theta-d was not designed for the helicopter (or not reset): A0 is " +
                std::to_string(A0.rows()) + "x" + std::to_string(A0.cols()));
  // R = L Lᵀ as the controller factors it: R⁻¹ and L⁻ᵀ, g0 L⁻ᵀ and Y0 = T0 g0 L⁻ᵀ.
  const Eigen::Index m = settings.R.rows();
  const Eigen::LLT<Eigen::MatrixXd> llt(settings.R);
  const Eigen::MatrixXd r_inverse = llt.solve(Eigen::MatrixXd::Identity(m, m));
  const Eigen::MatrixXd r_inverse_sqrt_t = llt.matrixU().solve(Eigen::MatrixXd::Identity(m, m));
  const Eigen::MatrixXd g0_scaled = controller.g0() * r_inverse_sqrt_t;
  const Eigen::MatrixXd y0 = controller.T0() * g0_scaled;

  ExportedDesign design;
  design.step_files = {"fixed_point.hpp", "theta_d_step.hpp"};
  design.input_weights = settings.R;
  design.initial_input = settings.initial_input;
  DesignSource& d = design.data;
  d.add_integer("terms", settings.terms);
  d.add_integer("fixed_point_iterations", settings.fixed_point_iterations);
  d.add_integer("feedforward_velocity", feedforward_velocity ? 1 : 0);
  d.add_scalar("fixed_point_tolerance", settings.fixed_point_tolerance);
  d.add_scalar("start_time", controller.start_time());
  d.add_array("initial_input", entries(settings.initial_input));
  d.add_array("k", entries(settings.k));
  d.add_array("l", entries(settings.l));
  d.add_array("r_inverse", row_major(r_inverse));
  d.add_array("r_inverse_sqrt_t", row_major(r_inverse_sqrt_t));
  d.add_array("a0", row_major(A0));
  d.add_array("g0_scaled", row_major(g0_scaled));
  d.add_array("t0", row_major(controller.T0()));
  d.add_array("y0", row_major(y0));
  const Unknowns unknowns = order_unknowns();
  d.add_integer("input_row_unknowns", unknowns.input_row_count);
  d.add_indices("unknown_row", unknowns.row);
  d.add_indices("unknown_col", unknowns.col);
  // L⁻¹ on the unknowns in that order: the solver's packed_inverse() solves Ac0ᵀX + XAc0 + Q = 0,
  // i.e. X = L⁻¹(−Q). N = 1 needs none.
  std::vector<double> inverse;
  if (settings.terms > 1) {
    const ConstantLyapunovSolver solver(controller.Ac0());
    const auto count = unknowns.row.size();
    inverse.reserve(count * count);
    for (std::size_t a = 0; a < count; ++a)
      for (std::size_t b = 0; b < count; ++b)
        inverse.push_back(-solver.packed_inverse()(ConstantLyapunovSolver::packed_index(unknowns.row[a], unknowns.col[a]),
                                                   ConstantLyapunovSolver::packed_index(unknowns.row[b], unknowns.col[b])));
  }
  d.add_array("lyapunov_inverse", inverse);
  design.wrappers = fixed_point_step_wrappers("thetad_onboard::ThetaDState<T, Design<double>::terms>", "theta_d", "");
  return design;
}

}  // namespace thetad
