#pragma once
// The blob table: one row per blob, as CSV (header first) or JSON Lines (one object per blob).
// Columns: frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy and, when asked, mu20,mu11,mu02, then, with a
// calibration, X,Y (workspace mm of wcx,wcy). Real numbers are
// printed in the shortest form that reads back to the same double, so nothing is lost.

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <opencv2/core/types.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "pipeline/value.hpp"

namespace neopipe::pipeline::io {

enum class TableFormat { csv, jsonl };

/// Maps a frame's weighted centroids (px) to the workspace (mm), all at once (a lens model undistorts
/// a batch faster than point by point).
using WorldMap = std::function<std::vector<cv::Point2d>(const std::vector<cv::Point2d>&)>;

struct TableOptions {
  TableFormat format = TableFormat::csv;
  bool moments = false;  ///< add the second central moments mu20, mu11, mu02
  WorldMap to_world;     ///< if set, add X,Y: the weighted centroid on the workspace (mm)
};

/// csv for ".csv", jsonl for ".jsonl" / ".ndjson"; nullopt otherwise.
std::optional<TableFormat> table_format_for(const std::string& path);

class BlobTableWriter {
 public:
  /// Writes to `out` (which must outlive the writer), e.g. std::cout.
  BlobTableWriter(std::ostream& out, TableOptions options);
  /// Creates (truncates) `path`; throws std::runtime_error naming it if it cannot.
  BlobTableWriter(const std::string& path, TableOptions options);

  /// Writes one frame's rows and flushes, so rows of processed frames survive a later failure.
  void write(std::int64_t frame, const BlobList& blobs);
  std::int64_t rows() const { return rows_; }

 private:
  void header();

  std::unique_ptr<std::ofstream> file_;
  std::ostream* out_;
  TableOptions options_;
  std::string path_;
  fmt::memory_buffer buffer_;  ///< one frame's rows, written at once; keeps its capacity
  std::int64_t rows_ = 0;
};

}  // namespace neopipe::pipeline::io
