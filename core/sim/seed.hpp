#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace thetad::sim {

// A seed as a user writes it (`--seed`, a scenario's `seed`, a campaign's `base_seed`): a whole
// decimal number from 0 to 2^64 - 1. Anything else ("-1", "", "1.5", "0x10", a number beyond
// 2^64 - 1) is nullopt, so that no reader wraps or saturates it silently.
std::optional<std::uint64_t> parse_seed(std::string_view text);

// What parse_seed accepts, for error messages.
inline constexpr std::string_view kSeedExpected = "expected a whole number from 0 to 18446744073709551615";

}  // namespace thetad::sim
