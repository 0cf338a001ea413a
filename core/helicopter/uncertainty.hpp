#pragma once

#include <array>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "core/helicopter/parameters.hpp"
#include "core/helicopter/state.hpp"

namespace thetad::heli {

// Table 1 of the paper (docs/model.md §9.1): 45 uncertainties in percent. Parameter entries perturb the
// plant's true parameters once per run (p_true = p_nom (1 + pct/100 xi), xi in [-1, 1]); noise
// entries act on a signal at every controller sample (applied by the simulator).
enum class UncertaintyCategory { measurement, actuator, wind_noise, model_noise, parameter };

struct UncertaintyEntry {
  int number;             // row of Table 1 (1-based)
  std::string_view name;  // as in the table
  double percent;
  UncertaintyCategory category;
  // What the entry acts on: measurement -> State index (kXp..kB1); actuator -> Input index;
  // wind_noise -> body axis 0, 1, 2 (u_w, v_w, w_w); model_noise -> 0 V_imr, 1 V_itr;
  // parameter -> -1 (see `parameter`).
  int channel;
  double Parameters::*parameter;  // the perturbed field for parameter entries, else nullptr
};

inline constexpr int kUncertaintyCount = 45;
inline constexpr int kParameterUncertaintyCount = 21;

// clang-format off
inline constexpr std::array<UncertaintyEntry, kUncertaintyCount> kUncertaintyTable = {{
    {1,  "a1",          5.0, UncertaintyCategory::measurement, kA1, nullptr},
    {2,  "b1",          5.0, UncertaintyCategory::measurement, kB1, nullptr},
    {3,  "delta_ped",   5.0, UncertaintyCategory::actuator,    kPed, nullptr},
    {4,  "a_mr",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::lift_slope_mr},
    {5,  "A_lon_nom",   5.0, UncertaintyCategory::parameter,   -1, &Parameters::a_lon_nom},
    {6,  "B_lat_nom",   5.0, UncertaintyCategory::parameter,   -1, &Parameters::b_lat_nom},
    {7,  "c_mr",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::chord_mr},
    {8,  "g",           0.5, UncertaintyCategory::parameter,   -1, &Parameters::gravity},
    {9,  "h_mr",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::h_mr},
    {10, "h_tr",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::h_tr},
    {11, "I_xx",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::ixx},
    {12, "I_yy",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::iyy},
    {13, "I_zz",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::izz},
    {14, "K_beta",      5.0, UncertaintyCategory::parameter,   -1, &Parameters::k_beta},
    {15, "K_mu",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::k_mu},
    {16, "l_tr",        5.0, UncertaintyCategory::parameter,   -1, &Parameters::l_tr},
    {17, "m",           0.5, UncertaintyCategory::parameter,   -1, &Parameters::mass},
    {18, "p",           5.0, UncertaintyCategory::measurement, kP, nullptr},
    {19, "q",           5.0, UncertaintyCategory::measurement, kQ, nullptr},
    {20, "r",           5.0, UncertaintyCategory::measurement, kR, nullptr},
    {21, "R_mr",        0.5, UncertaintyCategory::parameter,   -1, &Parameters::radius_mr},
    {22, "T_mr",        5.0, UncertaintyCategory::actuator,    kTmr, nullptr},
    {23, "u",           5.0, UncertaintyCategory::measurement, kU, nullptr},
    {24, "v",           5.0, UncertaintyCategory::measurement, kV, nullptr},
    {25, "w",           5.0, UncertaintyCategory::measurement, kW, nullptr},
    {26, "u_w",         5.0, UncertaintyCategory::wind_noise,  0, nullptr},
    {27, "v_w",         5.0, UncertaintyCategory::wind_noise,  1, nullptr},
    {28, "w_w",         5.0, UncertaintyCategory::wind_noise,  2, nullptr},
    {29, "V_imr",      10.0, UncertaintyCategory::model_noise, 0, nullptr},
    {30, "V_itr",      10.0, UncertaintyCategory::model_noise, 1, nullptr},
    {31, "x_p",         5.0, UncertaintyCategory::measurement, kXp, nullptr},
    {32, "y_p",         5.0, UncertaintyCategory::measurement, kYp, nullptr},
    {33, "z_p",         5.0, UncertaintyCategory::measurement, kZp, nullptr},
    {34, "Y_ped_tr",   10.0, UncertaintyCategory::parameter,   -1, &Parameters::y_ped_tr},
    {35, "delta_col",   5.0, UncertaintyCategory::actuator,    kCol, nullptr},
    {36, "delta_lon",   5.0, UncertaintyCategory::actuator,    kLon, nullptr},
    {37, "delta_lat",   5.0, UncertaintyCategory::actuator,    kLat, nullptr},
    {38, "phi",         5.0, UncertaintyCategory::measurement, kPhi, nullptr},
    {39, "theta",       5.0, UncertaintyCategory::measurement, kTheta, nullptr},
    {40, "psi",         5.0, UncertaintyCategory::measurement, kPsi, nullptr},
    {41, "eta_w",       1.0, UncertaintyCategory::parameter,   -1, &Parameters::eta_w},
    {42, "lambda0",     1.0, UncertaintyCategory::parameter,   -1, &Parameters::lambda0},
    {43, "rho",         0.5, UncertaintyCategory::parameter,   -1, &Parameters::rho},
    {44, "tau_e",       5.0, UncertaintyCategory::parameter,   -1, &Parameters::tau_e},
    {45, "Omega_nom",   5.0, UncertaintyCategory::parameter,   -1, &Parameters::omega_nom},
}};
// clang-format on

std::string_view to_string(UncertaintyCategory category);

// Per-channel noise levels in percent, read from kUncertaintyTable (the simulator's source):
// measurement by State index kXp..kB1 (14), actuator by Input index (5), wind by body axis (3),
// induced velocities [0] V_imr, [1] V_itr.
std::array<double, kPhysicalStateDim> measurement_noise_percents();
std::array<double, kInputDim> actuator_noise_percents();
std::array<double, 3> wind_noise_percents();
std::array<double, 2> induced_velocity_noise_percents();

// One row of the report of a parameter draw.
struct UncertaintyReport {
  int number;
  std::string name;
  double percent;  // the bound as applied: Table 1's times the scale for parameter entries
  UncertaintyCategory category;
  bool per_sample;  // noise entries: applied by the simulator at every sample; xi = 0, factor = 1 here
  double xi;        // parameter entries: the draw in [-1, 1]
  double factor;    // parameter entries: 1 + percent/100 xi, applied to the nominal value
};

struct PerturbedParameters {
  Parameters parameters;
  std::vector<UncertaintyReport> report;  // all 45 entries, in table order
};

// Throws thetad::Error unless `scale` is a valid multiplier of the parameter bounds (see below).
void check_uncertainty_scale(double scale);

// xi for the 21 parameter entries, in table order.
using ParameterDraw = std::array<double, kParameterUncertaintyCount>;

// `xi` as a draw; throws thetad::Error unless it has the 21 entries, each finite and in [-1, 1].
ParameterDraw parameter_draw(const std::vector<double>& xi);

// The names of the 21 parameter entries (Table 1's), in table order.
std::array<std::string_view, kParameterUncertaintyCount> parameter_uncertainty_names();

// Draws xi ~ U[-1, 1] for the 21 parameter entries in table order from rng (portable: built from
// the generator's raw 64-bit output, so a seed gives the same draw on every standard library).
// `scale` multiplies every bound (0: the nominal plant, 1: Table 1, 2: twice its percents); the
// same xi are drawn whatever the scale, so a sweep over it varies the bounds, not the draw.
PerturbedParameters perturbed_parameters(const Parameters& nominal, std::mt19937_64& rng, double scale = 1.0);
// The same with a given xi (e.g. a sign vector for worst cases); throws thetad::Error when an
// entry is outside [-1, 1] or not finite, or when `scale` is negative, not finite, or so large that
// a factor 1 + scale percent/100 xi could reach zero (scale >= 10 with Table 1's 10 % entries).
PerturbedParameters perturbed_parameters(const Parameters& nominal, const ParameterDraw& xi, double scale = 1.0);
// All xi = +1.
PerturbedParameters worst_case_parameters(const Parameters& nominal);

}  // namespace thetad::heli
