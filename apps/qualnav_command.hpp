#pragma once
// `neopipe qualnav`: Qualnav's topological tools (spec qualnav.md §4, §5). `regions`: the orientation
// regions of a world's marbles (the arrangement of their LPB lines: lines, crossings with their
// multiplicity, region count), optionally drawn; `productions`: the table of heading productions.

#include <CLI/CLI.hpp>
#include <string>

namespace neopipe::apps {

struct QualnavArgs {
  bool json = false;
  std::string world;      ///< regions --world
  std::string landmarks;  ///< regions --landmarks i,j,...: empty for every marble
  std::string plot;       ///< regions --plot out.png|.svg
};

CLI::App* add_qualnav_command(CLI::App& app, QualnavArgs& args);
/// Runs the subcommand of `qualnav` parsed.
int qualnav_command(const CLI::App& qualnav, const QualnavArgs& args);

}  // namespace neopipe::apps
