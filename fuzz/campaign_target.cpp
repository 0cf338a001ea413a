// A campaign file (`thetad campaign run`): a campaign that loads has at least one run, and every
// factor of every cell is within its factor's range.
#include <cmath>

#include "campaigns/campaign.hpp"
#include "fuzz/target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return thetad::fuzz::run(data, size, [](const std::string& text) {
    const thetad::Campaign campaign = thetad::parse_campaign(text, "fuzz-campaign.yaml");
    if (campaign.run_count() < 1)
      thetad::fuzz::finding("a loaded campaign without runs", std::to_string(campaign.run_count()));
    for (const thetad::FactorValues& cell : campaign.cells) {
      for (const auto& [name, value] : cell) {
        const thetad::Factor* factor = thetad::find_factor(name);
        if (factor == nullptr || !std::isfinite(value) || value < factor->min || value > factor->max)
          thetad::fuzz::finding("a loaded campaign with a factor out of its range", name + " = " + std::to_string(value));
      }
    }
  });
}
