// "The navigator never sees ground truth": its sources, and those of nav/common which it links,
// include nothing from the simulator, the rig, the calibration or the map-maker (the build also
// refuses to link them: nav/navigator/CMakeLists.txt).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace {

struct Scan {
  int files = 0;
  int includes = 0;
};

// Fails for every include of a forbidden module and every CMake line linking one.
Scan expect_isolated(const std::filesystem::path& dir) {
  Scan scan;
  const std::regex include(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".hpp" && ext != ".h" && ext != ".txt") continue;
    ++scan.files;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (std::regex_search(line, m, include)) {
        ++scan.includes;
        const std::string header = m[1];
        for (const char* forbidden : {"sim/", "rig/", "nav/mapmaker/", "calib/", "apps/"}) {
          EXPECT_NE(header.rfind(forbidden, 0), 0u) << entry.path() << ": " << line;
        }
      }
      if (ext == ".txt" && line.find("target_link_libraries(") != std::string::npos) {
        for (const char* forbidden : {"neopipe_sim", "neopipe_rig", "neopipe_mapmaker", "neopipe_calib"}) {
          EXPECT_EQ(line.find(forbidden), std::string::npos) << entry.path() << ": " << line;
        }
      }
    }
  }
  return scan;
}

TEST(NavigatorIsolation, SourcesIncludeNeitherTheSimulatorNorTheMapMaker) {
  const std::filesystem::path dir = std::filesystem::path(NEOPIPE_NAV_SOURCE_DIR) / "navigator";
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  const Scan scan = expect_isolated(dir);
  EXPECT_GE(scan.files, 5);
  EXPECT_GT(scan.includes, 10);
}

TEST(NavigatorIsolation, TheSharedNavigationLibraryIsAsBlind) {
  const std::filesystem::path dir = std::filesystem::path(NEOPIPE_NAV_SOURCE_DIR) / "common";
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  const Scan scan = expect_isolated(dir);
  EXPECT_GE(scan.files, 4);
  EXPECT_GT(scan.includes, 3);
}

}  // namespace
