#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "settings/run_controls.hpp"
#include "settings/run_settings.hpp"

namespace thetad {

// The conditions a campaign may fix or sweep: the run settings with a factor column
// (settings/run_settings.hpp), so a campaign's cell means what `thetad run` with the same
// override means. A factor's value is a number (a choice's position, a switch's 0 or 1).
using Factor = RunSetting;

// Every factor with a column of its own, in the order the runs table lists them (not the families
// plant.NAME and initial_state.I, whose members a campaign's runs table adds as it names them).
const std::vector<Factor>& factors();
// The factor named `name`, or by its name before docs/glossary.md (`duration` for `duration_s`),
// or the family that `name` is a member of (plant.epsilon: plant.NAME); nullptr when there is none.
const Factor* find_factor(std::string_view name);
// "uncertainty_scale, noise_scale, ..., plant.NAME, initial_state.I" for messages.
std::string factor_names();

// The position of `name` among factor.choices; nullopt when it is not one of them.
std::optional<double> choice_value(const Factor& factor, std::string_view name);

// A set of factor values: one sweep cell (fixed factors included), in the order they were given.
using FactorValues = std::vector<std::pair<std::string, double>>;

// The value `text` gives `factor`: a number, or for a factor with names one of them; throws
// thetad::Error saying what was expected, or that the value is outside the factor's range. The one
// reading of a factor's value: campaign files, `thetad run --set` and Python's keywords.
double factor_value(const Factor& factor, const std::string& text);

// `controls` with every value of `values` applied (each by its factor's override, RunSetting::set).
void apply(const FactorValues& values, RunControls& controls);

}  // namespace thetad
