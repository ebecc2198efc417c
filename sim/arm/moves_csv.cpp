#include "sim/arm/moves_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <string_view>
#include <vector>

namespace neopipe::sim {
namespace {

constexpr std::array<std::string_view, 3> kColumns{"dx", "dy", "dtheta"};

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  for (;;) {
    const auto comma = line.find(',');
    fields.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return fields;
    line.remove_prefix(comma + 1);
  }
}

/// The number `text` holds, or a cause for the error message.
std::optional<double> parse_number(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);  // from_chars refuses a leading '+'
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

MovesReader::MovesReader(std::string path) : path_(std::move(path)) {
  std::error_code ec;
  if (!std::filesystem::exists(path_, ec)) throw MovesError(path_ + ": no such file");
  if (std::filesystem::is_directory(path_, ec)) throw MovesError(path_ + ": a directory, not a moves file");
  in_.open(path_, std::ios::binary);
  if (!in_) throw MovesError(path_ + ": cannot be read");
  std::string header;
  if (!std::getline(in_, header)) throw MovesError(path_ + ": empty; the first line must be the header dx,dy,dtheta");
  line_ = 1;
  if (header.starts_with("\xEF\xBB\xBF")) header.erase(0, 3);
  if (!header.empty() && header.back() == '\r') header.pop_back();
  const auto names = split_fields(header);
  if (!std::equal(names.begin(), names.end(), kColumns.begin(), kColumns.end())) {
    fail(fmt::format("the header must be 'dx,dy,dtheta' (mm, mm, degrees), not '{}'", header));
  }
}

std::optional<MoveLine> MovesReader::next() {
  std::string text;
  while (std::getline(in_, text)) {
    ++line_;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (trim(text).empty()) continue;
    const auto fields = split_fields(text);
    if (fields.size() != kColumns.size()) {
      fail(fmt::format("expected 3 fields dx,dy,dtheta, found {}", fields.size()));
    }
    std::array<double, 3> values{};
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const auto value = parse_number(fields[i]);
      if (!value) fail(fmt::format("{} '{}' is not a number", kColumns[i], fields[i]));
      if (!std::isfinite(*value)) fail(fmt::format("{} '{}' is not a finite number", kColumns[i], fields[i]));
      values[i] = *value;
    }
    return MoveLine{line_, values[0], values[1], values[2]};
  }
  if (in_.bad()) fail("read failed");
  return std::nullopt;
}

void MovesReader::fail(const std::string& cause) const {
  throw MovesError(fmt::format("{}:{}: {}", path_, line_, cause));
}

}  // namespace neopipe::sim
