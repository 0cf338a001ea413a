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

// SplitMix64's finalizer (Steele, Lea & Flood 2014): consecutive inputs give uncorrelated outputs.
std::uint64_t splitmix64(std::uint64_t z);

// The random sources added after the paper's (docs/model.md §15). Each draws from its own
// generator, seeded with stream_seed(run seed, stream), never from the run's generator: switching
// one on leaves every paper draw, and every other stream, as it was.
enum class RandomStream : std::uint64_t {
  turbulence = 1,    // Dryden and Gauss-Markov turbulence, at the plant rate
  sensor_noise = 2,  // additive sensor noise, per controller sample
  sensor_bias = 3,   // sensor biases, drawn once per run
};
std::uint64_t stream_seed(std::uint64_t run_seed, RandomStream stream);

}  // namespace thetad::sim
