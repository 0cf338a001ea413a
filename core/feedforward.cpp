#include "core/feedforward.hpp"

#include "core/error.hpp"

namespace thetad {

std::string feedforward_name(FeedForward feedforward) {
  return kFeedForwardChoices[static_cast<int>(feedforward)];
}

FeedForward parse_feedforward(const std::string& name) {
  for (int i = 0; i < 3; ++i)
    if (name == kFeedForwardChoices[i]) return static_cast<FeedForward>(i);
  throw Error("feedforward must be none, velocity or velocity+trim, got '" + name + "'");
}

}  // namespace thetad
