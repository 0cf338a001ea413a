#include <Eigen/Cholesky>

#include "core/error.hpp"
#include "export/design_export.hpp"
#include "export/onboard/helicopter_sdc.hpp"

namespace thetad {

ExportedDesign sdre_design(const SdreController& controller) {
  const SdreSettings& settings = controller.settings();
  if (settings.mode != SdreSettings::Mode::capped)
    throw Error("export: sdre is exportable in mode capped only (a fixed number of Newton–Kleinman steps per "
                "pass and no Riccati solver on board; docs/onboard.md), not in mode " +
                controller.name().substr(5));
  const Eigen::MatrixXd& P0 = controller.last_value_matrix();
  if (P0.rows() != thetad_onboard::kStates || settings.R.rows() != thetad_onboard::kInputs)
    throw Error("export: sdre was not designed for the helicopter (or not reset): P is " + std::to_string(P0.rows()) +
                "x" + std::to_string(P0.cols()));
  const Eigen::Index m = settings.R.rows();
  const Eigen::LLT<Eigen::MatrixXd> llt(settings.R);
  ExportedDesign design;
  design.step_files = {"fixed_point.hpp", "lyapunov_schur.hpp", "sdre_step.hpp"};
  design.input_weights = settings.R;
  design.initial_input = settings.initial_input;
  DesignSource& d = design.data;
  d.add_integer("newton_iterations", settings.newton_iterations);
  d.add_integer("fixed_point_iterations", settings.fixed_point_iterations);
  d.add_scalar("fixed_point_tolerance", settings.fixed_point_tolerance);
  d.add_scalar("start_time", 0.0);
  d.add_array("initial_input", entries(settings.initial_input));
  d.add_array("q", row_major(settings.Q));
  d.add_array("r_cholesky", row_major(Eigen::MatrixXd(llt.matrixL())));
  d.add_array("r_inverse", row_major(llt.solve(Eigen::MatrixXd::Identity(m, m))));
  // The library's cold solve at the design point (SdreController::reset in the capped mode).
  d.add_array("p0", row_major(P0));
  design.carried_state = [](const Controller& library) {
    return row_major(dynamic_cast<const SdreController&>(library).last_value_matrix());
  };
  design.wrappers =
      fixed_point_step_wrappers("thetad_onboard::SdreState<T>", "sdre",
                                "// Loads the design point's P (the library's cold solve there) and the initial input.\n") +
      "// The P the next step's Newton–Kleinman starts from (row-major 18 x 18), likewise.\n"
      "template <class T>\n"
      "void set_value_matrix(State<T>& state, const double* value) {\n"
      "  for (int e = 0; e < thetad_onboard::kStates * thetad_onboard::kStates; ++e) state.value[e] = T(value[e]);\n"
      "}\n";
  design.carried_state_setter = "set_value_matrix";
  return design;
}

}  // namespace thetad
