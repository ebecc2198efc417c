#include "apps/cli_support.hpp"

#include <algorithm>
#include <cstdio>

namespace neopipe::apps {

void print_error(const std::string& command, const std::string& message) {
  std::string one_line = message;
  std::replace(one_line.begin(), one_line.end(), '\n', ' ');
  const std::string who = command.empty() ? "neopipe" : "neopipe " + command;
  std::fprintf(stderr, "%s: error: %s\n", who.c_str(), one_line.c_str());
}

}  // namespace neopipe::apps
