// Like every navigator, Qualnav's topological level never sees ground truth: nav/qualnav/topology/
// includes nothing from the simulator, the rig, the calibration, the map-maker or the apps, and its
// CMake links none of them (the build refuses too: neopipe_forbid_ground_truth).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

TEST(QualnavIsolation, TopologyIncludesNothingThatKnowsTheTruth) {
  const std::filesystem::path dir(NEOPIPE_QUALNAV_TOPOLOGY_SOURCE_DIR);
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  const std::regex include(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  int files = 0;
  int includes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".hpp" && ext != ".txt") continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (std::regex_search(line, m, include)) {
        ++includes;
        const std::string header = m[1];
        for (const char* forbidden : {"sim/", "rig/", "nav/mapmaker/", "nav/navigator/", "calib/", "apps/", "opencv"}) {
          EXPECT_NE(header.rfind(forbidden, 0), 0U) << entry.path() << ": " << line;
        }
      }
      if (line.find("target_link_libraries(") != std::string::npos) {
        for (const char* forbidden : {"neopipe_sim", "neopipe_rig", "neopipe_mapmaker", "neopipe_calib", "opencv"}) {
          EXPECT_EQ(line.find(forbidden), std::string::npos) << entry.path() << ": " << line;
        }
      }
    }
  }
  EXPECT_EQ(files, 9);  // four headers, four sources, CMakeLists.txt
  EXPECT_GT(includes, 20);
}
