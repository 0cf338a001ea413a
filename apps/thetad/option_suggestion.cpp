#include "apps/thetad/option_suggestion.hpp"

#include <algorithm>
#include <vector>

namespace thetad::app {

namespace {

// Levenshtein's distance: insertions, deletions and substitutions.
std::size_t edits(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The subcommand being parsed: the deepest one the command line named.
const CLI::App& parsed(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) return parsed(*sub);
  return app;
}

}  // namespace

std::string option_suggestion(const CLI::App& app) {
  const CLI::App& command = parsed(app);
  std::vector<std::string> known;
  for (const CLI::Option* option : command.get_options())
    for (const std::string& name : option->get_lnames()) known.push_back("--" + name);
  constexpr std::size_t kClose = 2;
  for (const std::string& given : app.remaining()) {
    if (!given.starts_with("--")) continue;
    const std::string flag = given.substr(0, given.find('='));
    const auto best = std::min_element(known.begin(), known.end(), [&](const std::string& a, const std::string& b) {
      return edits(flag, a) < edits(flag, b);
    });
    if (best != known.end() && edits(flag, *best) <= kClose) return " (did you mean " + *best + "?)";
  }
  return "";
}

}  // namespace thetad::app
