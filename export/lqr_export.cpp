#include "core/error.hpp"
#include "export/design_export.hpp"
#include "export/onboard/helicopter_sdc.hpp"

namespace thetad {

ExportedDesign lqr_design(const LqrController& controller, const Eigen::MatrixXd& input_weights) {
  const Eigen::MatrixXd& K = controller.design().K;
  const OperatingPoint& point = controller.operating_point();
  if (K.rows() != thetad_onboard::kInputs || point.tracking.size() != thetad_onboard::kStates)
    throw Error("export: lqr was not designed for the helicopter: its gain is " + std::to_string(K.rows()) + "x" +
                std::to_string(K.cols()));
  ExportedDesign design;
  design.step_files = {"lqr_step.hpp"};
  design.input_weights = input_weights;
  design.initial_input = Eigen::VectorXd::Zero(K.rows());
  DesignSource& d = design.data;
  d.add_integer("design_states", K.cols());
  d.add_scalar("start_time", 0.0);
  d.add_array("input", entries(point.input));
  d.add_array("tracking", entries(point.tracking.head(K.cols())));
  d.add_array("gain", row_major(K));
  design.wrappers =
      "template <class T>\n"
      "using State = thetad_onboard::LqrState<T>;\n"
      "template <class T>\n"
      "void reset(State<T>& state) { thetad_onboard::lqr_reset<T, Design<T>>(state); }\n"
      "template <class T>\n"
      "thetad_onboard::Status step(State<T>& state, T t, const T* measured, const thetad_onboard::Reference<T>& reference,\n"
      "                            T* u) {\n"
      "  return thetad_onboard::lqr_step<T, Design<T>>(state, t, measured, reference, u);\n"
      "}\n"
      "// The LQR starts from nothing: nothing to set (the same call as every exported step's).\n"
      "template <class T>\n"
      "void set_applied_input(State<T>&, const T*) {}\n";
  return design;
}

}  // namespace thetad
