#pragma once
// The blob table: one row per blob, as CSV (header first) or JSON Lines (one object per blob).
// Columns: frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy and, when asked, mu20,mu11,mu02, then, with a
// calibration, X,Y (workspace mm of wcx,wcy). Real numbers are
// printed in the shortest form that reads back to the same double, so nothing is lost.

#include <fmt/format.h>

#include <cstdint>
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
  ~BlobTableWriter();
  BlobTableWriter(const BlobTableWriter&) = delete;
  BlobTableWriter& operator=(const BlobTableWriter&) = delete;

  /// Writes one frame's rows and flushes, so rows of processed frames survive a later failure. When
  /// a file cannot take them all (a full disk), the frame's part already written is cut off again,
  /// so the file ends with the last whole frame, and the error names the file and the cause.
  void write(std::int64_t frame, const BlobList& blobs);
  std::int64_t rows() const { return rows_; }

 private:
  void header();
  void put(const char* data, std::size_t size);

  int fd_ = -1;                  ///< the file's descriptor (a path given), else -1
  std::int64_t committed_ = 0;   ///< bytes of the file that end a whole frame
  std::ostream* out_ = nullptr;  ///< the stream (no path given)
  TableOptions options_;
  std::string path_;
  fmt::memory_buffer buffer_;  ///< one frame's rows, written at once; keeps its capacity
  std::int64_t rows_ = 0;
};

}  // namespace neopipe::pipeline::io
