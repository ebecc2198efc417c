#include "apps/cli_support.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <vector>

#include "nav/mapmaker/planner.hpp"

namespace neopipe::apps {

void print_error(const std::string& command, const std::string& message) {
  std::string one_line = message;
  std::replace(one_line.begin(), one_line.end(), '\n', ' ');
  const std::string who = command.empty() ? "neopipe" : "neopipe " + command;
  std::fprintf(stderr, "%s: error: %s\n", who.c_str(), one_line.c_str());
}

CLI::Option* add_cost_option(CLI::App* cmd, std::string& cost) {
  std::vector<std::string> names;
  names.reserve(nav::mapmaker::kCriteria.size());
  for (const auto c : nav::mapmaker::kCriteria) names.emplace_back(nav::mapmaker::criterion_name(c));
  return cmd
      ->add_option("--cost", cost,
                   "Path criterion: distance (min D), reliability (min U = -log R), ratio (min D/R, the paper's "
                   "compromise), landmark (min "
                   "landmark-based distance: the straight lines between successive landmarks)")
      ->capture_default_str()
      ->check(CLI::IsMember(names));
}

}  // namespace neopipe::apps
