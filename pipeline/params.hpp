#pragma once
// Reads a node's parameters from its YAML map, with defaults and ranges, and reports mistakes at
// the parameter's position in the spec. finish() rejects parameters nobody asked for, so a typo
// ("treshold: 40") is an error, not a silently ignored setting.

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "pipeline/source_location.hpp"

namespace neopipe::pipeline {

class ParamReader {
 public:
  ParamReader(const YAML::Node& params, SourceLocation node_where, std::string kernel);

  bool has(const std::string& name);
  int get_int(const std::string& name, int fallback, int min, int max);
  double get_double(const std::string& name, double fallback, double min, double max);
  bool get_bool(const std::string& name, bool fallback);
  std::string get_string(const std::string& name, const std::string& fallback);
  std::optional<std::string> get_optional_string(const std::string& name);
  /// One of `choices`.
  std::string get_choice(const std::string& name, const std::string& fallback,
                         std::initializer_list<const char*> choices);
  /// A list of integers, of exactly `count` entries when count > 0.
  std::vector<int> get_int_list(const std::string& name, size_t count, int min, int max);
  /// The raw value (null if absent); marks the name as known.
  YAML::Node raw(const std::string& name);

  /// Where the parameter's value is (or the node, if the parameter is absent).
  SourceLocation where(const std::string& name) const;
  [[noreturn]] void fail(const std::string& name, const std::string& message) const;
  /// Throws GraphError on any parameter that was never asked for.
  void finish() const;

 private:
  YAML::Node value(const std::string& name);

  YAML::Node params_;
  SourceLocation node_where_;
  std::string kernel_;
  std::set<std::string> known_;
};

}  // namespace neopipe::pipeline
