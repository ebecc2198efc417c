#pragma once
// The blob table: one row per blob, as CSV (header first) or JSON Lines (one object per blob).
// Columns: frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy and, when asked, mu20,mu11,mu02. Real numbers are
// printed in the shortest form that reads back to the same double, so nothing is lost.

#include <cstdint>
#include <fstream>
#include <memory>
#include <ostream>
#include <string>

#include "pipeline/value.hpp"

namespace neopipe::pipeline::io {

enum class TableFormat { csv, jsonl };

struct TableOptions {
  TableFormat format = TableFormat::csv;
  bool moments = false;  ///< add the second central moments mu20, mu11, mu02
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
  std::string buffer_;
  std::int64_t rows_ = 0;
};

}  // namespace neopipe::pipeline::io
