// Includes every header the package installed (installed_headers.hpp, listed by CMakeLists.txt) and
// calls into each library, so that a header that needs an uninstalled one, or a library whose
// dependencies the package does not carry, fails to build here: building and linking is the test.
//   all_headers [world FILE | calibration FILE | map TEXT | route - | trials - | qrm -]

#include <cstdio>
#include <string>

#include "installed_headers.hpp"

int main(int argc, char** argv) {
  // Each call only when asked for, so the program runs without files; the linker resolves them all.
  if (argc > 2) {
    const std::string what = argv[1];
    const std::string arg = argv[2];
    if (what == "world") std::printf("%zu objects\n", neopipe::sim::load_world(arg).objects.size());
    if (what == "calibration")
      std::printf("%s\n", neopipe::calib::model_name(neopipe::calib::load_calibration(arg).model).c_str());
    if (what == "map") std::printf("%zu entries\n", neopipe::nav::parse_custom_map(arg).entries.size());
    if (what == "route") std::printf("%s", neopipe::nav::mapmaker::route_table({}).c_str());
    if (what == "qrm") std::printf("%d triples\n", neopipe::nav::qrm::composition_table().feasible_triples());
    if (what == "trials") std::printf("%lld\n", static_cast<long long>(neopipe::rig::compare_paired({}, {}).journeys));
  }
  std::printf("neopipe %s: every installed header compiles\n", neopipe::version);
  return 0;
}
