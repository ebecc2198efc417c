// "The navigator never sees ground truth": its sources include nothing from the simulator or the
// map-maker (the build also refuses to link them: nav/navigator/CMakeLists.txt).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace {

TEST(NavigatorIsolation, SourcesIncludeNeitherTheSimulatorNorTheMapMaker) {
  const std::filesystem::path dir = NEOPIPE_NAVIGATOR_SOURCE_DIR;
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  const std::regex include(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  int files = 0;
  int includes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".hpp" && ext != ".h" && ext != ".txt") continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (std::regex_search(line, m, include)) {
        ++includes;
        const std::string header = m[1];
        EXPECT_NE(header.rfind("sim/", 0), 0u) << entry.path() << ": " << line;
        EXPECT_NE(header.rfind("nav/mapmaker/", 0), 0u) << entry.path() << ": " << line;
        EXPECT_NE(header.rfind("calib/", 0), 0u) << entry.path() << ": " << line;
      }
      if (ext == ".txt") {
        EXPECT_EQ(
            line.find("target_link_libraries(neopipe_navigator") != std::string::npos &&
                (line.find("neopipe_sim") != std::string::npos || line.find("neopipe_mapmaker") != std::string::npos),
            false)
            << entry.path() << ": " << line;
      }
    }
  }
  EXPECT_GE(files, 5);
  EXPECT_GT(includes, 10);
}

}  // namespace
