#pragma once
// The moves file `neopipe sim arm` reads: relative moves in the tool frame, one per line.
//
//   dx,dy,dtheta        header, required: mm, mm, degrees (counter-clockwise)
//   100,0,0             move 100 mm along the tool's x axis
//   0,-20.5,90          move 20.5 mm along its -y axis, then turn a quarter turn left
//
// Spaces around fields, blank lines, CRLF line ends and a UTF-8 byte order mark are accepted.

#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>

namespace neopipe::sim {

/// A moves file that cannot be read; the message is one line, "<path>:<line>: <cause>" (or
/// "<path>: <cause>" when no line is to blame).
class MovesError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct MoveLine {
  int line = 0;           ///< 1-based line number in the file (the header is line 1)
  double dx = 0;          ///< mm, tool frame
  double dy = 0;          ///< mm, tool frame
  double dtheta_deg = 0;  ///< degrees, as written
};

/// Reads a moves file one line at a time, so that a caller can act on every good line before a bad
/// one stops it.
class MovesReader {
 public:
  /// Opens the file and checks its header. Throws MovesError.
  explicit MovesReader(std::string path);

  /// The next move, or nullopt at the end of the file. Throws MovesError naming the line.
  std::optional<MoveLine> next();

  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const std::string& cause) const;

  std::string path_;
  std::ifstream in_;
  int line_ = 0;
};

}  // namespace neopipe::sim
