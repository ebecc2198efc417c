#pragma once
// What the pipeline tests share: a per-process temporary folder, YAML written line by line, and a
// field-by-field blob table comparison.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <initializer_list>
#include <opencv2/core.hpp>
#include <string>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/value.hpp"

namespace neopipe::pipeline::testing {

/// A fresh folder under GoogleTest's temporary directory, removed afterwards. Unique per process,
/// so concurrent runs of the suite do not share files.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::path(::testing::TempDir()) / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string str() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

/// Joins lines with '\n', so a test's YAML shows its line numbers one entry per line.
inline std::string yaml_lines(std::initializer_list<const char*> lines) {
  std::string s;
  for (const char* l : lines) s.append(l).append("\n");
  return s;
}

/// Every field equal (exactly: the engine's results do not depend on how they were computed).
inline void expect_same_blobs(const BlobList& a, const BlobList& b, const std::string& what = "") {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(what + (what.empty() ? "" : ", ") + "blob " + std::to_string(i));
    EXPECT_EQ(a[i].area, b[i].area);
    EXPECT_EQ(a[i].x0, b[i].x0);
    EXPECT_EQ(a[i].y0, b[i].y0);
    EXPECT_EQ(a[i].width, b[i].width);
    EXPECT_EQ(a[i].height, b[i].height);
    EXPECT_EQ(a[i].cx, b[i].cx);
    EXPECT_EQ(a[i].cy, b[i].cy);
    EXPECT_EQ(a[i].wcx, b[i].wcx);
    EXPECT_EQ(a[i].wcy, b[i].wcy);
    EXPECT_EQ(a[i].mu20, b[i].mu20);
    EXPECT_EQ(a[i].mu11, b[i].mu11);
    EXPECT_EQ(a[i].mu02, b[i].mu02);
    EXPECT_EQ(a[i].value, b[i].value);
  }
}

/// Same size, type and pixels.
inline bool same_image(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && (a.empty() || cv::norm(a, b, cv::NORM_INF) == 0);
}

/// Port values equal: images pixel for pixel, histograms count for count, blob tables field by field.
inline void expect_same_value(const Value& a, const Value& b, const std::string& what) {
  ASSERT_EQ(a.index(), b.index()) << what;
  if (const auto* ma = std::get_if<cv::Mat>(&a)) {
    EXPECT_TRUE(same_image(*ma, std::get<cv::Mat>(b))) << what;
  } else if (const auto* ha = std::get_if<Histogram>(&a)) {
    EXPECT_TRUE(*ha == std::get<Histogram>(b)) << what;
  } else if (const auto* ba = std::get_if<BlobList>(&a)) {
    expect_same_blobs(*ba, std::get<BlobList>(b), what);
  }
}

inline CompiledGraph compile_yaml(const std::string& yaml, const KernelRegistry& registry = standard_kernels()) {
  return compile(parse_graph_spec(yaml, "spec.yaml"), registry);
}

inline CompiledGraph compile_example(const std::string& file) {
  return compile(load_graph_spec(std::string(NEOPIPE_EXAMPLES_DIR) + "/" + file), standard_kernels());
}

}  // namespace neopipe::pipeline::testing
