// Like the navigator, the qualitative relational map never sees ground truth: nav/qrm/ includes
// nothing from the simulator, the rig, the calibration, the map-maker or the apps, and its CMake
// links none of them (the build refuses too: nav/qrm/CMakeLists.txt).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

TEST(QrmIsolation, SourcesIncludeNothingThatKnowsTheTruth) {
  const std::filesystem::path dir(NEOPIPE_QRM_SOURCE_DIR);
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  const std::regex include(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  int files = 0;
  int includes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".hpp" && ext != ".in" && ext != ".txt") continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (std::regex_search(line, m, include)) {
        ++includes;
        const std::string header = m[1];
        for (const char* forbidden : {"sim/", "rig/", "nav/mapmaker/", "nav/navigator/", "calib/", "apps/"}) {
          EXPECT_NE(header.rfind(forbidden, 0), 0U) << entry.path() << ": " << line;
        }
      }
      for (const char* forbidden : {"neopipe_sim", "neopipe_rig", "neopipe_mapmaker", "neopipe_calib"}) {
        if (line.find("target_link_libraries(") != std::string::npos) {
          EXPECT_EQ(line.find(forbidden), std::string::npos) << entry.path() << ": " << line;
        }
      }
    }
  }
  EXPECT_GE(files, 20);
  EXPECT_GT(includes, 30);
}
