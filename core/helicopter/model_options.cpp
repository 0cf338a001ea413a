#include "core/helicopter/model_options.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace thetad::heli {

namespace {

using Options = ModelOptions;

[[noreturn]] void bad_value(std::string_view name, std::string_view value, std::string_view accepted) {
  throw Error("model option '" + std::string(name) + "': unknown value '" + std::string(value) +
              "' (accepted: " + std::string(accepted) + ")");
}

int parse_sign(std::string_view name, std::string_view value) {
  if (value == "+1" || value == "1") return 1;
  if (value == "-1") return -1;
  bad_value(name, value, "+1, -1");
}

std::string print_sign(int sign) { return sign > 0 ? "+1" : "-1"; }

bool parse_on_off(std::string_view name, std::string_view value) {
  if (value == "on") return true;
  if (value == "off") return false;
  bad_value(name, value, "on, off");
}

// An enum switch: its value names in the order of the enumerators.
template <typename Enum, std::size_t N>
Enum parse_enum(std::string_view name, std::string_view value, const std::array<std::string_view, N>& spellings) {
  const auto it = std::find(spellings.begin(), spellings.end(), value);
  if (it == spellings.end()) {
    std::string accepted;
    for (const auto s : spellings) accepted += (accepted.empty() ? "" : ", ") + std::string(s);
    bad_value(name, value, accepted);
  }
  return static_cast<Enum>(it - spellings.begin());
}

template <typename Enum, std::size_t N>
std::string print_enum(Enum value, const std::array<std::string_view, N>& spellings) {
  return std::string(spellings[static_cast<std::size_t>(value)]);
}

constexpr std::array<std::string_view, 2> kFlapInflowSignSource = {"mu", "u_a"};
constexpr std::array<std::string_view, 3> kYawInertia = {"minus_rotor", "izz", "plus_rotor"};
constexpr std::array<std::string_view, 2> kRotorSpeedModel = {"thrust_inversion", "governor"};
constexpr std::array<std::string_view, 2> kSolidity = {"nomenclature", "computed"};
constexpr std::array<std::string_view, 2> kTailRotorTorque = {"none", "profile"};
constexpr std::array<std::string_view, 2> kInducedVelocityModel = {"constant", "lambda0_omega_r"};

[[noreturn]] void bad_name(std::string_view name) {
  std::string known;
  for (const auto n : Options::names) known += (known.empty() ? "" : ", ") + std::string(n);
  throw Error("unknown model option '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace

ModelOptions ModelOptions::paper() {
  ModelOptions o;
  o.lateral_flap_speed_sign = 1;
  o.collective_trim_offset = false;
  o.flap_inflow_sign_source = FlapInflowSignSource::mu;
  o.fuselage_downwash_sign = 1;
  o.tail_rotor_velocity_sign = 1;
  o.horizontal_tail_sign = 1;
  o.solidity = Solidity::nomenclature;
  return o;
}

ModelOptions ModelOptions::preset(std::string_view name) {
  if (name == "resolved") return resolved();
  if (name == "paper") return paper();
  throw Error("unknown model preset '" + std::string(name) + "' (known: resolved, paper)");
}

void ModelOptions::set(std::string_view name, std::string_view value) {
  if (name == "lateral_flap_speed_sign") lateral_flap_speed_sign = parse_sign(name, value);
  else if (name == "collective_trim_offset") collective_trim_offset = parse_on_off(name, value);
  else if (name == "flap_inflow_sign_source") flap_inflow_sign_source = parse_enum<FlapInflowSignSource>(name, value, kFlapInflowSignSource);
  else if (name == "fuselage_downwash_sign") fuselage_downwash_sign = parse_sign(name, value);
  else if (name == "tail_rotor_velocity_sign") tail_rotor_velocity_sign = parse_sign(name, value);
  else if (name == "yaw_inertia") yaw_inertia = parse_enum<YawInertia>(name, value, kYawInertia);
  else if (name == "rotor_speed_model") rotor_speed_model = parse_enum<RotorSpeedModel>(name, value, kRotorSpeedModel);
  else if (name == "horizontal_tail_sign") horizontal_tail_sign = parse_sign(name, value);
  else if (name == "solidity") solidity = parse_enum<Solidity>(name, value, kSolidity);
  else if (name == "tail_rotor_torque") tail_rotor_torque = parse_enum<TailRotorTorque>(name, value, kTailRotorTorque);
  else if (name == "induced_velocity_model") induced_velocity_model = parse_enum<InducedVelocityModel>(name, value, kInducedVelocityModel);
  else bad_name(name);
}

std::string ModelOptions::get(std::string_view name) const {
  if (name == "lateral_flap_speed_sign") return print_sign(lateral_flap_speed_sign);
  if (name == "collective_trim_offset") return collective_trim_offset ? "on" : "off";
  if (name == "flap_inflow_sign_source") return print_enum(flap_inflow_sign_source, kFlapInflowSignSource);
  if (name == "fuselage_downwash_sign") return print_sign(fuselage_downwash_sign);
  if (name == "tail_rotor_velocity_sign") return print_sign(tail_rotor_velocity_sign);
  if (name == "yaw_inertia") return print_enum(yaw_inertia, kYawInertia);
  if (name == "rotor_speed_model") return print_enum(rotor_speed_model, kRotorSpeedModel);
  if (name == "horizontal_tail_sign") return print_sign(horizontal_tail_sign);
  if (name == "solidity") return print_enum(solidity, kSolidity);
  if (name == "tail_rotor_torque") return print_enum(tail_rotor_torque, kTailRotorTorque);
  if (name == "induced_velocity_model") return print_enum(induced_velocity_model, kInducedVelocityModel);
  bad_name(name);
}

std::string ModelOptions::to_string() const {
  std::string out;
  for (const auto name : names) out += (out.empty() ? "" : ", ") + std::string(name) + "=" + get(name);
  return out;
}

}  // namespace thetad::heli
