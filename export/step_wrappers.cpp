#include "export/design_export.hpp"

namespace thetad {

std::string fixed_point_step_wrappers(const std::string& state_type, const std::string& prefix,
                                      const std::string& reset_comment) {
  return "template <class T>\n"
         "using State = " + state_type + ";\n" + reset_comment +
         "template <class T>\n"
         "void reset(State<T>& state) { thetad_onboard::" + prefix + "_reset<T, Design<T>>(state); }\n"
         "template <class T>\n"
         "thetad_onboard::Status step(State<T>& state, T t, const T* measured, const thetad_onboard::Reference<T>& reference,\n"
         "                            T* u) {\n"
         "  return thetad_onboard::" + prefix + "_step<T, Design<T>>(state, kHelicopter, t, measured, reference, u);\n"
         "}\n"
         "// The input the fixed point starts from at the next step (the last applied one): for a check that\n"
         "// starts in the middle of a recorded flight.\n"
         "template <class T>\n"
         "void set_applied_input(State<T>& state, const T* input) {\n"
         "  for (int k = 0; k < thetad_onboard::kInputs; ++k) state.applied[k] = input[k];\n"
         "}\n";
}

}  // namespace thetad
