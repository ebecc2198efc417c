#include "nav/qrm/composition.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>

#include "nav/qrm/edc.hpp"
#include "nav/qrm/region_constraints.hpp"

namespace neopipe::nav::qrm {
namespace {

constexpr const char* kMagic = "neopipe-qrm-composition";

std::string entry_line(State s1, State s2, StateSet states) {
  std::string line = std::to_string(s1) + ' ' + std::to_string(s2) + ' ';
  bool first = true;
  for (const State s : states) {
    if (!first) line += ',';
    line += std::to_string(s);
    first = false;
  }
  return line;
}

std::string hex64(std::uint64_t v) {
  std::ostringstream out;
  out << std::hex;
  out.width(16);
  out.fill('0');
  out << v;
  return out.str();
}

}  // namespace

std::uint64_t fnv1a64(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::vector<Quadratic> composition_problem(State s1, State s2, State s3) {
  check_state(s1);
  check_state(s2);
  check_state(s3);
  constexpr int n = 4;
  const AffinePoint a{Affine::constant(0), Affine::constant(0)};
  const AffinePoint b{Affine::constant(0), Affine::constant(1)};
  const AffinePoint c{Affine::unknown(0), Affine::unknown(1)};
  const AffinePoint d{Affine::unknown(2), Affine::unknown(3)};
  std::vector<Quadratic> g = region_constraints(n, a, b, c, s1);
  for (const auto& part : {region_constraints(n, b, c, d, s2), region_constraints(n, a, b, d, s3)}) {
    g.insert(g.end(), part.begin(), part.end());
  }
  return g;
}

Feasibility composition_feasible(State s1, State s2, State s3, double half_width, int depth) {
  const std::vector<Quadratic> g = composition_problem(s1, s2, s3);
  Box box;
  for (int i = 0; i < 4; ++i) {
    box.lo[i] = -half_width;
    box.hi[i] = half_width;
  }
  return find_feasible(g, box, depth);
}

CompositionEntries generate_composition_entries(const std::function<void(int, int)>& progress) {
  CompositionEntries entries{};
  int done = 0;
  for (State s1 = 1; s1 <= kStateCount; ++s1) {
    for (State s2 = 1; s2 <= kStateCount; ++s2) {
      for (State s3 = 1; s3 <= kStateCount; ++s3) {
        if (composition_feasible(s1, s2, s3).witness) entries[s1 - 1][s2 - 1].insert(s3);
      }
      if (progress) progress(++done, kStateCount * kStateCount);
    }
  }
  return entries;
}

CompositionTable::CompositionTable(const CompositionEntries& entries) : entries_(entries) {
  for (int x = 0; x < kStateCount; ++x) {
    for (unsigned half = 0; half < 1024; ++half) {
      StateSet lo;
      StateSet hi;
      for (int bit = 0; bit < 10; ++bit) {
        if (((half >> bit) & 1U) == 0) continue;
        lo |= entries_[x][bit];
        hi |= entries_[x][bit + 10];
      }
      low_[x][half] = lo.mask();
      high_[x][half] = hi.mask();
    }
  }
}

StateSet CompositionTable::operator()(State s1, State s2) const {
  check_state(s1);
  check_state(s2);
  return entries_[s1 - 1][s2 - 1];
}

int CompositionTable::feasible_triples() const {
  int n = 0;
  for (const auto& row : entries_) {
    for (const StateSet e : row) n += e.count();
  }
  return n;
}

std::string format_composition_table(const CompositionEntries& entries) {
  std::string body;
  for (State s1 = 1; s1 <= kStateCount; ++s1) {
    for (State s2 = 1; s2 <= kStateCount; ++s2) body += entry_line(s1, s2, entries[s1 - 1][s2 - 1]) + '\n';
  }
  std::ostringstream out;
  out << "# neopipe qrm composition table (spec qrm.md section 4, docs/qrm.md): comp(s1, s2) is the set of\n"
         "# states of AB:D possible when AB:C = s1 and BC:D = s2, each one proved feasible by branch and\n"
         "# bound with A = (0,0), B = (0,1), C and D in the box [-8, 8]^4, to depth 40.\n"
         "# Written by `neopipe qrm tables --write FILE`. One line per (s1, s2): s1 s2 states; then the\n"
         "# FNV-1a 64-bit checksum of those lines (each with its newline).\n"
      << kMagic << ' ' << kCompositionFormatVersion << " box " << kCompositionHalfWidth << " depth "
      << kCompositionDepth << '\n'
      << body << "checksum " << hex64(fnv1a64(body)) << '\n';
  return out.str();
}

CompositionEntries parse_composition_table(const std::string& text, const std::string& origin) {
  std::istringstream in(text);
  std::string line;
  int number = 0;
  const auto fail = [&](const std::string& cause) {
    throw CompositionTableError(origin + ": line " + std::to_string(number) + ": " + cause);
  };
  const auto next = [&]() {
    while (std::getline(in, line)) {
      ++number;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (!line.empty() && line.front() != '#') return true;
    }
    return false;
  };
  if (!next()) throw CompositionTableError(origin + ": empty, not a composition table");
  {
    std::istringstream header(line);
    std::string magic;
    std::string box_word;
    std::string depth_word;
    int version = 0;
    double box = 0;
    int depth = 0;
    if (!(header >> magic) || magic != kMagic)
      fail("not a composition table (expected '" + std::string(kMagic) + " ...')");
    if (!(header >> version >> box_word >> box >> depth_word >> depth) || box_word != "box" || depth_word != "depth") {
      fail("malformed header (expected '" + std::string(kMagic) + " VERSION box H depth D')");
    }
    if (version != kCompositionFormatVersion) {
      fail("format version " + std::to_string(version) + ", this neopipe reads version " +
           std::to_string(kCompositionFormatVersion));
    }
    if (box != kCompositionHalfWidth || depth != kCompositionDepth) {
      std::ostringstream why;
      why << "computed with box " << box << " depth " << depth << ", expected box " << kCompositionHalfWidth
          << " depth " << kCompositionDepth;
      fail(why.str());
    }
  }
  CompositionEntries entries{};
  std::string body;
  for (State s1 = 1; s1 <= kStateCount; ++s1) {
    for (State s2 = 1; s2 <= kStateCount; ++s2) {
      if (!next()) {
        throw CompositionTableError(origin + ": truncated: no line for comp(" + std::to_string(s1) + ", " +
                                    std::to_string(s2) + ")");
      }
      std::istringstream fields(line);
      int a = 0;
      int b = 0;
      std::string states;
      std::string extra;
      if (!(fields >> a >> b >> states) || (fields >> extra)) fail("expected 's1 s2 states', got '" + line + "'");
      if (a != s1 || b != s2) {
        fail("expected the entry of (" + std::to_string(s1) + ", " + std::to_string(s2) + "), got (" +
             std::to_string(a) + ", " + std::to_string(b) + ")");
      }
      StateSet set;
      int previous = 0;
      std::size_t at = 0;
      while (at <= states.size()) {
        const std::size_t comma = std::min(states.find(',', at), states.size());
        int s = 0;
        const char* first = states.data() + at;
        const char* last = states.data() + comma;
        const auto [ptr, ec] = std::from_chars(first, last, s);
        if (ec != std::errc{} || ptr != last || s < 1 || s > kStateCount) {
          fail("'" + states + "' is not a list of states 1..20");
        }
        if (s <= previous) fail("states '" + states + "' are not strictly increasing");
        previous = s;
        set.insert(s);
        at = comma + 1;
      }
      entries[s1 - 1][s2 - 1] = set;
      body += entry_line(s1, s2, set) + '\n';
    }
  }
  if (!next()) throw CompositionTableError(origin + ": truncated: no checksum line");
  const std::string expected = "checksum " + hex64(fnv1a64(body));
  if (line.rfind("checksum ", 0) != 0) fail("expected the checksum line, got '" + line + "'");
  if (line != expected)
    fail("checksum mismatch: the file says '" + line.substr(9) + "', its entries give '" + expected.substr(9) +
         "' (corrupt or edited table)");
  if (next()) fail("unexpected text after the checksum line");
  return entries;
}

SamplingReport sample_composition(const CompositionTable& table, std::int64_t samples, std::uint64_t seed,
                                  const std::function<void(std::int64_t)>& progress) {
  SamplingReport report;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> box(-kCompositionHalfWidth, kCompositionHalfWidth);
  std::uniform_real_distribution<double> unit(0, 1);
  const Eigen::Vector2d a{0, 0};
  const Eigen::Vector2d b{0, 1};
  const auto near = [&](const Eigen::Vector2d& centre) {
    const double r = std::pow(10.0, -2 + 3 * unit(rng));
    const double t = 2 * std::numbers::pi * unit(rng);
    return Eigen::Vector2d(centre + r * Eigen::Vector2d(std::cos(t), std::sin(t)));
  };
  std::vector<bool> seen(static_cast<std::size_t>(kStateCount * kStateCount * kStateCount), false);
  for (std::int64_t n = 0; n < samples; ++n) {
    const Eigen::Vector2d c = n % 2 == 0 ? Eigen::Vector2d(box(rng), box(rng)) : near(n % 4 == 1 ? a : b);
    const Eigen::Vector2d d = n % 3 == 0 ? Eigen::Vector2d(box(rng), box(rng)) : near(n % 3 == 1 ? c : b);
    ++report.samples;
    if (progress && (n & 0xFFFFF) == 0) progress(n);
    const State s1 = classify(a, b, c);
    const State s2 = classify(b, c, d);
    const State s3 = classify(a, b, d);
    if (s1 == 0 || s2 == 0 || s3 == 0) {
      ++report.degenerate;
      continue;
    }
    if (!table(s1, s2).contains(s3)) {
      if (report.outside++ == 0) report.first_outside = {s1, s2, s3};
      continue;
    }
    const int index = ((s1 - 1) * kStateCount + (s2 - 1)) * kStateCount + (s3 - 1);
    if (!seen[static_cast<std::size_t>(index)]) {
      seen[static_cast<std::size_t>(index)] = true;
      ++report.triples_seen;
    }
  }
  return report;
}

CompositionEntries load_composition_table(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw CompositionTableError(path + ": cannot open the composition table");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw CompositionTableError(path + ": cannot read the composition table");
  return parse_composition_table(text.str(), path);
}

}  // namespace neopipe::nav::qrm
