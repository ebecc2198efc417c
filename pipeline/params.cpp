#include "pipeline/params.hpp"

#include <sstream>

namespace neopipe::pipeline {
namespace {

template <class T>
bool parse_number(const std::string& text, T& out) {
  std::istringstream is(text);
  is >> out;
  return !is.fail() && is.eof();
}

}  // namespace

ParamReader::ParamReader(const YAML::Node& params, SourceLocation node_where, std::string kernel)
    : params_(params), node_where_(std::move(node_where)), kernel_(std::move(kernel)) {}

YAML::Node ParamReader::value(const std::string& name) {
  known_.insert(name);
  // A default-constructed YAML::Node is a defined null, which would read as "given"; absent must
  // be undefined.
  if (!params_ || !params_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node& p = params_;
  return p[name];
}

bool ParamReader::has(const std::string& name) {
  return static_cast<bool>(value(name));
}

YAML::Node ParamReader::raw(const std::string& name) {
  return value(name);
}

SourceLocation ParamReader::where(const std::string& name) const {
  if (params_ && params_.IsMap()) {
    const YAML::Node& p = params_;
    const YAML::Node v = p[name];
    if (v && !v.Mark().is_null() && v.Mark().line >= 0) {
      return {node_where_.file, v.Mark().line + 1, v.Mark().column + 1};
    }
  }
  return node_where_;
}

void ParamReader::fail(const std::string& name, const std::string& message) const {
  throw GraphError(where(name), kernel_ + " parameter '" + name + "': " + message);
}

int ParamReader::get_int(const std::string& name, int fallback, int min, int max) {
  const YAML::Node v = value(name);
  if (!v) return fallback;
  long long x = 0;
  if (!v.IsScalar() || !parse_number(v.Scalar(), x)) fail(name, "expected an integer");
  if (x < min || x > max) {
    fail(name, std::to_string(x) + " is out of range " + std::to_string(min) + ".." + std::to_string(max));
  }
  return static_cast<int>(x);
}

double ParamReader::get_double(const std::string& name, double fallback, double min, double max) {
  const YAML::Node v = value(name);
  if (!v) return fallback;
  double x = 0;
  if (!v.IsScalar() || !parse_number(v.Scalar(), x)) fail(name, "expected a number");
  if (!(x >= min && x <= max)) {
    std::ostringstream os;
    os << x << " is out of range " << min << ".." << max;
    fail(name, os.str());
  }
  return x;
}

bool ParamReader::get_bool(const std::string& name, bool fallback) {
  const YAML::Node v = value(name);
  if (!v) return fallback;
  const std::string s = v.IsScalar() ? v.Scalar() : "";
  if (s == "true" || s == "yes" || s == "on" || s == "1") return true;
  if (s == "false" || s == "no" || s == "off" || s == "0") return false;
  fail(name, "expected true or false");
}

std::optional<std::string> ParamReader::get_optional_string(const std::string& name) {
  const YAML::Node v = value(name);
  if (!v) return std::nullopt;
  if (!v.IsScalar()) fail(name, "expected a single value");
  return v.Scalar();
}

std::string ParamReader::get_string(const std::string& name, const std::string& fallback) {
  return get_optional_string(name).value_or(fallback);
}

std::string ParamReader::get_choice(const std::string& name, const std::string& fallback,
                                    std::initializer_list<const char*> choices) {
  const std::string s = get_string(name, fallback);
  std::string list;
  for (const char* c : choices) {
    if (s == c) return s;
    list += list.empty() ? c : std::string(", ") + c;
  }
  fail(name, "'" + s + "' is not one of " + list);
}

std::vector<int> ParamReader::get_int_list(const std::string& name, size_t count, int min, int max) {
  const YAML::Node v = value(name);
  if (!v || !v.IsSequence()) fail(name, "expected a list of integers");
  if (count > 0 && v.size() != count) {
    fail(name, "expected " + std::to_string(count) + " entries, got " + std::to_string(v.size()));
  }
  std::vector<int> out;
  for (const auto& e : v) {
    long long x = 0;
    if (!e.IsScalar() || !parse_number(e.Scalar(), x) || x < min || x > max) {
      fail(name, "entry " + std::to_string(out.size()) + " must be an integer in " + std::to_string(min) + ".." +
                     std::to_string(max));
    }
    out.push_back(static_cast<int>(x));
  }
  return out;
}

void ParamReader::finish() const {
  if (!params_ || !params_.IsMap()) return;
  for (const auto& kv : params_) {
    const std::string name = kv.first.Scalar();
    if (known_.count(name) != 0) continue;
    std::string list;
    for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
    SourceLocation at = node_where_;
    if (!kv.first.Mark().is_null() && kv.first.Mark().line >= 0) {
      at = {node_where_.file, kv.first.Mark().line + 1, kv.first.Mark().column + 1};
    }
    throw GraphError(at, "unknown parameter '" + name + "' for kernel '" + kernel_ + "'" +
                             (list.empty() ? " (it takes none)" : " (known: " + list + ")"));
  }
}

}  // namespace neopipe::pipeline
