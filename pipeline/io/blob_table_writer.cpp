#include "pipeline/io/blob_table_writer.hpp"

#include <fcntl.h>
#include <fmt/compile.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <utility>

namespace neopipe::pipeline::io {

std::optional<TableFormat> table_format_for(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".csv") return TableFormat::csv;
  if (ext == ".jsonl" || ext == ".ndjson") return TableFormat::jsonl;
  return std::nullopt;
}

BlobTableWriter::BlobTableWriter(std::ostream& out, TableOptions options)
    : out_(&out), options_(std::move(options)), path_("<stdout>") {
  header();
}

// A file is written through its descriptor, not an ofstream: a failed write() leaves its cause in
// errno at once (the stream's was long overwritten: "No space left on device" came out as "No such
// file or directory"), and says how much went out, so a partly written frame can be cut off.
BlobTableWriter::BlobTableWriter(const std::string& path, TableOptions options)
    : fd_(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)),
      options_(std::move(options)),
      path_(path) {
  if (fd_ < 0) throw std::runtime_error(path + ": cannot create: " + std::strerror(errno));
  try {
    header();
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

BlobTableWriter::~BlobTableWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void BlobTableWriter::put(const char* data, std::size_t size) {
  if (fd_ < 0) {
    out_->write(data, static_cast<std::streamsize>(size));
    out_->flush();
    if (!*out_) throw std::runtime_error(path_ + ": write failed");
    return;
  }
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd_, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int cause = n < 0 ? errno : ENOSPC;
      // Best effort: a file that cannot be cut (a device) keeps what it took.
      if (::ftruncate(fd_, committed_) == 0) ::lseek(fd_, committed_, SEEK_SET);
      throw std::runtime_error(fmt::format("{}: write failed: {} (the table keeps its {} rows of whole frames)", path_,
                                           std::strerror(cause), rows_));
    }
    done += static_cast<std::size_t>(n);
  }
  committed_ += static_cast<std::int64_t>(size);
}

void BlobTableWriter::header() {
  if (options_.format != TableFormat::csv) return;
  const std::string line = fmt::format("frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy{}{}\n",
                                       options_.moments ? ",mu20,mu11,mu02" : "", options_.to_world ? ",X,Y" : "");
  put(line.data(), line.size());
}

void BlobTableWriter::write(std::int64_t frame, const BlobList& blobs) {
  // On a video with hundreds of blobs a frame, formatting the table was an eighth of `neopipe run`'s CPU
  // (docs/performance.md): formats are compiled (FMT_COMPILE: no format string parsed per row) and rows go to a
  // buffer reused from frame to frame. Each {} is the same fmt::detail::write as the runtime format's, so the text,
  // doubles in their shortest round-trip form included, is unchanged (BlobTableWriter tests compare it character
  // for character).
  buffer_.clear();
  auto it = fmt::appender(buffer_);
  std::vector<cv::Point2d> world;
  if (options_.to_world) {
    std::vector<cv::Point2d> centres;
    centres.reserve(blobs.size());
    for (const auto& b : blobs) centres.emplace_back(b.wcx, b.wcy);
    world = options_.to_world(centres);
  }
  for (size_t i = 0; i < blobs.size(); ++i) {
    const auto& b = blobs[i];
    if (options_.format == TableFormat::csv) {
      it = fmt::format_to(it, FMT_COMPILE("{},{},{},{},{},{},{},{},{},{},{}"), frame, i, b.area, b.cx, b.cy, b.x0, b.y0,
                          b.width, b.height, b.wcx, b.wcy);
      if (options_.moments) it = fmt::format_to(it, FMT_COMPILE(",{},{},{}"), b.mu20, b.mu11, b.mu02);
      if (options_.to_world) it = fmt::format_to(it, FMT_COMPILE(",{},{}"), world[i].x, world[i].y);
      *it++ = '\n';
    } else {
      it = fmt::format_to(it,
                          FMT_COMPILE(R"({{"frame":{},"blob":{},"area":{},"cx":{},"cy":{},"x0":{},"y0":{},"w":{},)"
                                      R"("h":{},"wcx":{},"wcy":{})"),
                          frame, i, b.area, b.cx, b.cy, b.x0, b.y0, b.width, b.height, b.wcx, b.wcy);
      if (options_.moments) {
        it = fmt::format_to(it, FMT_COMPILE(R"(,"mu20":{},"mu11":{},"mu02":{})"), b.mu20, b.mu11, b.mu02);
      }
      if (options_.to_world) it = fmt::format_to(it, FMT_COMPILE(R"(,"X":{},"Y":{})"), world[i].x, world[i].y);
      it = fmt::format_to(it, FMT_COMPILE("}}\n"));
    }
  }
  put(buffer_.data(), buffer_.size());
  rows_ += static_cast<std::int64_t>(blobs.size());
}

}  // namespace neopipe::pipeline::io
