#include "nav/common/custom_map.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>

namespace neopipe::nav {

std::optional<int> MapEntry::verified_qoc() const {
  for (const RecoveryRule& r : rules) {
    if (!r.corner) return r.qoc;
  }
  return std::nullopt;
}

bool MapEntry::verify_only_in_doubt() const {
  for (const RecoveryRule& r : rules) {
    if (!r.corner) return r.only_in_doubt;
  }
  return false;
}

std::optional<QuadrantPattern> MapEntry::verified_quadrants() const {
  for (const RecoveryRule& r : rules) {
    if (!r.corner) return r.quadrants;
  }
  return std::nullopt;
}

const RecoveryRule* MapEntry::recovery_for(int qoc) const {
  for (const RecoveryRule& r : rules) {
    if (r.corner && r.qoc == qoc) return &r;
  }
  return nullptr;
}

std::string format_quadrants(const QuadrantPattern& pattern) {
  std::string out;
  for (const Corner q : kCorners) {
    const Occupancy o = pattern[static_cast<std::size_t>(index(q))];
    if (o == Occupancy::empty) continue;
    if (!out.empty()) out += ' ';
    if (o == Occupancy::unsure) out += '~';
    out += corner_name(q);
  }
  return out.empty() ? "none" : out;
}

bool quadrants_allow(const QuadrantPattern& pattern, int qoc) {
  const auto occupied = std::count(pattern.begin(), pattern.end(), Occupancy::occupied);
  const auto unsure = std::count(pattern.begin(), pattern.end(), Occupancy::unsure);
  return occupied <= qoc && qoc <= occupied + unsure;
}

namespace {
std::string format_slide_goal(const SlideGoal& g) {
  const auto mm = [](double v) { return std::to_string(std::lround(v)); };
  return '@' + mm(g.along) + '/' + mm(g.cross) + '~' + mm(g.along_tolerance) + '/' + mm(g.cross_tolerance);
}
}  // namespace

std::string format_entry(const MapEntry& entry) {
  std::string out = "(";
  out += description_name(entry.seek);
  if (entry.slide) out += std::string(", ") + std::string(trajectory_name(*entry.slide));
  if (entry.slide && entry.slide_limit) {
    out += ':';
    out += std::to_string(std::lround(*entry.slide_limit));
  }
  if (entry.slide && entry.slide_goal) {
    out += format_slide_goal(*entry.slide_goal);
  }
  for (const RecoveryRule& r : entry.rules) {
    out += ", (";
    out += std::to_string(r.qoc);
    if (r.quadrants) {
      out += ' ';
      out += format_quadrants(*r.quadrants);
    }
    out += ", ";
    out += r.corner ? std::string(corner_name(*r.corner)) + ", " + std::string(description_name(r.seek))
                    : (r.only_in_doubt ? "?" : "-");
    out += ")";
  }
  out += ", ";
  out += entry.adjust ? std::string(corner_name(*entry.adjust)) : "-";
  return out + ")";
}

std::string format_custom_map(const CustomMap& map) {
  std::string out = "(";
  for (std::size_t i = 0; i < map.entries.size(); ++i) out += (i ? ", " : "") + format_entry(map.entries[i]);
  return out + ")";
}

namespace {

// A recursive-descent reader over the grammar
//   map   := '(' [entry {',' entry}] ')'
//   entry := '(' DESC [',' TRAJ [':' MM]] {',' rule} ',' (CORNER | '-') ')'
//   rule  := '(' INT [QUADRANTS] ',' ((CORNER ',' DESC) | '-' | '?') ')'
//   QUADRANTS := 'none' | ['~'] CORNER {['~'] CORNER}
class Reader {
 public:
  explicit Reader(std::string_view text) : text_(text) {}

  CustomMap map() {
    CustomMap m;
    expect('(');
    if (!peek(')')) {
      do m.entries.push_back(entry());
      while (accept(','));
    }
    expect(')');
    skip_space();
    if (pos_ != text_.size()) fail("end of the map");
    return m;
  }

 private:
  MapEntry entry() {
    MapEntry e;
    expect('(');
    const std::string desc = word();
    const auto d = parse_description(desc);
    if (!d) fail("a description (Obvious, Isol, Far, Near or *)", desc);
    e.seek = *d;
    while (true) {
      expect(',');
      if (peek('(')) {
        e.rules.push_back(rule());
        continue;
      }
      const std::string w = word();
      const std::string kind = w.substr(0, w.find_first_of(":@"));
      if (kind == "Trajp" || kind == "Trajn") {
        if (e.slide || !e.rules.empty()) fail("a recovery rule or a corner", w);
        e.slide = kind == "Trajp" ? Direction::positive : Direction::negative;
        const std::size_t at = w.find('@');
        const std::string bound = w.substr(0, at);
        if (kind.size() < bound.size()) e.slide_limit = slide_limit(bound.substr(kind.size() + 1));
        if (at != std::string::npos) e.slide_goal = slide_goal(w.substr(at + 1));
        continue;
      }
      if (w == "-") break;
      const auto c = parse_corner(w);
      if (!c) fail("a corner (SE, SW, NE, NW) or -", w);
      e.adjust = *c;
      break;
    }
    expect(')');
    return e;
  }

  RecoveryRule rule() {
    RecoveryRule r;
    expect('(');
    const std::string k = word();
    int value = -1;
    const auto [end, ec] = std::from_chars(k.data(), k.data() + k.size(), value);
    if (ec != std::errc{} || end != k.data() + k.size() || value < 0 || value > 4) fail("a QOC 0..4", k);
    r.qoc = value;
    if (!peek(',')) {
      const std::size_t at = pos_;
      r.quadrants = quadrants();
      if (!quadrants_allow(*r.quadrants, value)) {
        pos_ = at;
        fail("quadrants that a QOC of " + std::to_string(value) + " can count", format_quadrants(*r.quadrants));
      }
    }
    expect(',');
    const std::string w = word();
    if (r.quadrants && w != "-" && w != "?") fail("- or ? after the quadrants of the verified QOC", w);
    if (w == "?") {
      r.only_in_doubt = true;
    } else if (w != "-") {
      const auto c = parse_corner(w);
      if (!c) fail("a corner (SE, SW, NE, NW), - or ?", w);
      r.corner = *c;
      expect(',');
      const std::string desc = word();
      const auto d = parse_description(desc);
      if (!d) fail("a description (Obvious, Isol, Far, Near or *)", desc);
      r.seek = *d;
    }
    expect(')');
    return r;
  }

  QuadrantPattern quadrants() {
    QuadrantPattern pattern{};
    pattern.fill(Occupancy::empty);
    const std::string first = word();
    if (first == "none") return pattern;
    for (std::string w = first;; w = word()) {
      const bool unsure = !w.empty() && w.front() == '~';
      const auto q = parse_corner(unsure ? std::string_view(w).substr(1) : std::string_view(w));
      if (!q) fail("a quadrant (SE, SW, NE, NW, ~ before an unsure one) or none", w);
      Occupancy& o = pattern[static_cast<std::size_t>(index(*q))];
      if (o != Occupancy::empty) fail("each quadrant once", w);
      o = unsure ? Occupancy::unsure : Occupancy::occupied;
      if (peek(',')) return pattern;
    }
  }

  // "85/-3~8/12": along/cross~along_tolerance/cross_tolerance, whole mm, tolerances > 0.
  SlideGoal slide_goal(const std::string& text) const {
    std::array<int, 4> v{};
    const char* p = text.data();
    const char* const end = text.data() + text.size();
    constexpr std::array<char, 4> kAfter{'/', '~', '/', '\0'};
    for (std::size_t k = 0; k < v.size(); ++k) {
      const auto [next, ec] = std::from_chars(p, end, v[k]);
      const bool last = k + 1 == v.size();
      if (ec != std::errc{} || (last ? next != end : next == end || *next != kAfter[k]) || (k >= 2 && v[k] <= 0))
        fail("a slide goal along/cross~along-tolerance/cross-tolerance in whole mm (tolerances > 0)", text);
      p = last ? next : next + 1;
    }
    return {static_cast<double>(v[0]), static_cast<double>(v[1]), static_cast<double>(v[2]), static_cast<double>(v[3])};
  }

  double slide_limit(const std::string& text) const {
    int value = -1;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || value <= 0)
      fail("a slide bound in whole mm > 0", text);
    return value;
  }

  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool peek(char c) {
    skip_space();
    return pos_ < text_.size() && text_[pos_] == c;
  }
  bool accept(char c) {
    if (!peek(c)) return false;
    ++pos_;
    return true;
  }
  void expect(char c) {
    if (!accept(c)) fail(std::string("'") + c + "'");
  }
  std::string word() {
    skip_space();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != ',' && text_[pos_] != '(' && text_[pos_] != ')' &&
           !std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      ++pos_;
    }
    return std::string(text_.substr(start, pos_ - start));
  }
  [[noreturn]] void fail(const std::string& expected, const std::string& found = "") const {
    std::string got = found;
    if (got.empty()) got = pos_ < text_.size() ? std::string(1, text_[pos_]) : "the end";
    throw CustomMapError("custom map: at character " + std::to_string(pos_ + 1) + ": expected " + expected +
                         ", found '" + got + "'");
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

}  // namespace

CustomMap parse_custom_map(std::string_view text) {
  return Reader(text).map();
}

}  // namespace neopipe::nav
