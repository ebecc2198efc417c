#pragma once
// What the fuzz targets share: the input bytes as a file, for the readers that take only a path.

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace neopipe::fuzz {

// A file in memory (memfd) rewritten for every input, which the readers open by name as
// /proc/self/fd/N: on a disk-backed /tmp, truncating and rewriting a real file costs more than
// most of the parsers themselves. Each process has its own, so parallel jobs never share one.
// None of the readers goes by the file's name.
class InputFile {
 public:
  InputFile() : fd_(::memfd_create("neopipe-fuzz-input", MFD_CLOEXEC)) {
    if (fd_ < 0) std::abort();
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  ~InputFile() { ::close(fd_); }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // Replaces the file's content with `data` and returns its path. A failure to write is the
  // harness's, not the reader's: abort, so that it cannot pass for a run without findings.
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    if (::ftruncate(fd_, 0) != 0) std::abort();
    for (std::size_t done = 0; done < size;) {
      const ::ssize_t n = ::pwrite(fd_, data + done, size - done, static_cast<::off_t>(done));
      if (n <= 0) std::abort();
      done += static_cast<std::size_t>(n);
    }
    return path_;
  }

 private:
  int fd_;
  std::string path_;
};

}  // namespace neopipe::fuzz
