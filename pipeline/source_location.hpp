#pragma once
// Where something in a graph spec came from, and the error that points there.

#include <stdexcept>
#include <string>

namespace neopipe::pipeline {

struct SourceLocation {
  std::string file;  ///< the spec's file name, or a description such as "<built-in blob graph>"
  int line = 0;      ///< 1-based; 0 when unknown (graphs built in C++)
  int column = 0;    ///< 1-based; 0 when unknown

  /// "file:line:column", "file:line" or "file", whichever is known.
  std::string str() const;
};

/// An invalid graph: its what() is "file:line:column: message", one line.
class GraphError : public std::runtime_error {
 public:
  GraphError(const SourceLocation& where, const std::string& message);
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

}  // namespace neopipe::pipeline
