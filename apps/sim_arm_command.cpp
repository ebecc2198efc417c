#include "apps/sim_arm_command.hpp"

#include <stdexcept>

namespace neopipe::apps {

// Placeholder until the arm lands (same session, branch sim-arm); never committed to a release.
void add_sim_arm_options(CLI::App& cmd, SimArmArgs& args) {
  cmd.add_option("--world", args.world, "World file (YAML)");
  cmd.add_option("--moves", args.moves, "Moves (CSV)");
}

int sim_arm_command(const SimArmArgs& /*args*/) {
  throw std::runtime_error("the simulated arm is not built yet");
}

}  // namespace neopipe::apps
