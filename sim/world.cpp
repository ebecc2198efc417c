#include "sim/world.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sim/neighbour_grid.hpp"

namespace neopipe::sim {
namespace {

class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}

  World read(const YAML::Node& root) const {
    if (!root.IsMap()) fail(root, "a world file is a map with 'size' and 'objects'");
    for (const auto& kv : root) {
      const std::string key = key_of(kv.first);
      if (key != "size" && key != "objects" && key != "marble_diameter" && key != "min_gap" && key != "seed") {
        fail(kv.first, "unknown key '" + key + "' (expected size, objects, marble_diameter, min_gap, seed)");
      }
    }
    World w;
    const YAML::Node size = root["size"];
    if (!size) fail(root, "missing 'size' ([W, H] in mm)");
    w.size = pair(size, "size");
    if (!(w.size.x() > 0 && w.size.y() > 0)) fail(size, "'size' must be two positive numbers [W, H] in mm");
    if (const YAML::Node d = root["marble_diameter"]) {
      w.marble_diameter = number(d, "marble_diameter");
      if (!(w.marble_diameter > 0)) fail(d, "'marble_diameter' must be positive");
    }
    const YAML::Node objects = root["objects"];
    if (!objects) fail(root, "missing 'objects' (a list of [x, y] in mm)");
    if (objects.IsNull()) return w;  // "objects:" with nothing after it: an empty world
    if (!objects.IsSequence()) fail(objects, "'objects' must be a list of [x, y] in mm");
    w.objects.reserve(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const YAML::Node o = objects[i];
      const Eigen::Vector2d p = pair(o, fmt::format("object {}", i));
      const double r = w.marble_diameter / 2;
      if (p.x() < r || p.y() < r || p.x() > w.size.x() - r || p.y() > w.size.y() - r) {
        fail(o, fmt::format("object {} at ({}, {}) is not wholly on the {} x {} mm workspace", i, p.x(), p.y(),
                            w.size.x(), w.size.y()));
      }
      w.objects.push_back(p);
      locations_.push_back(o.Mark());
    }
    const auto overlap = first_overlap(w, 0.0);
    if (overlap) {
      const auto [a, b] = *overlap;
      fail_at(locations_[b], fmt::format("object {} overlaps object {} (centres {:.4g} mm apart, diameter {} mm)", b, a,
                                         (w.objects[a] - w.objects[b]).norm(), w.marble_diameter));
    }
    return w;
  }

 private:
  [[noreturn]] void fail(const YAML::Node& n, const std::string& why) const { fail_at(n.Mark(), why); }
  [[noreturn]] void fail_at(const YAML::Mark& m, const std::string& why) const {
    if (m.is_null() || m.line < 0) throw WorldError(path_ + ": " + why);
    throw WorldError(fmt::format("{}:{}:{}: {}", path_, m.line + 1, m.column + 1, why));
  }
  // A map key as text. YAML allows any node as a key ("[0, 0]: 1"), and yaml-cpp's
  // as<std::string>() throws its own exception for those, which would escape as a crash instead of
  // a WorldError (found by fuzz/fuzz_world.cpp).
  std::string key_of(const YAML::Node& key) const {
    if (!key.IsScalar()) fail(key, "a key must be a single name");
    return key.Scalar();
  }
  double number(const YAML::Node& n, const std::string& what) const {
    if (!n.IsScalar()) fail(n, what + ": expected a number");
    try {
      const auto v = n.as<double>();
      if (!std::isfinite(v)) fail(n, what + ": expected a finite number");
      return v;
    } catch (const YAML::Exception&) {
      fail(n, what + ": '" + n.Scalar() + "' is not a number");
    }
  }
  Eigen::Vector2d pair(const YAML::Node& n, const std::string& what) const {
    if (!n.IsSequence() || n.size() != 2) fail(n, what + " must be a pair [x, y]");
    return {number(n[0], what), number(n[1], what)};
  }

  std::string path_;
  mutable std::vector<YAML::Mark> locations_;
};

}  // namespace

std::optional<std::pair<std::size_t, std::size_t>> first_overlap(const World& world, double min_gap) {
  const double min_distance = world.marble_diameter + min_gap;
  NeighbourGrid grid(world.size, min_distance);
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    if (const auto j = grid.any_within(world.objects[i], min_distance)) return std::pair{*j, i};
    grid.insert(world.objects[i], i);
  }
  return std::nullopt;
}

World load_world(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw WorldError(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) throw WorldError(path + ": a directory, not a world file");
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::ParserException& e) {
    throw WorldError(fmt::format("{}:{}:{}: not valid YAML: {}", path, e.mark.line + 1, e.mark.column + 1, e.msg));
  } catch (const YAML::BadFile&) {
    throw WorldError(path + ": cannot be read");
  }
  return Reader(path).read(root);
}

void check_world(const World& world, const std::string& origin) {
  const double r = world.marble_diameter / 2;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const Eigen::Vector2d& p = world.objects[i];
    if (!(p.x() >= r && p.y() >= r && p.x() <= world.size.x() - r && p.y() <= world.size.y() - r)) {
      throw WorldError(fmt::format("{}: object {} at ({}, {}) is not wholly on the {} x {} mm workspace", origin, i,
                                   p.x(), p.y(), world.size.x(), world.size.y()));
    }
  }
  if (const auto overlap = first_overlap(world, 0.0)) {
    throw WorldError(fmt::format("{}: object {} overlaps object {}", origin, overlap->second, overlap->first));
  }
}

void save_world(const World& world, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw WorldError(path + ": cannot be written");
  // {} prints the shortest text that reads back as the same double.
  out << fmt::format("size: [{}, {}]  # mm, workspace from (0,0) to (W,H); x East, y North\n", world.size.x(),
                     world.size.y());
  out << fmt::format("marble_diameter: {}  # mm\n", world.marble_diameter);
  out << "objects:  # [x, y] mm; object id = index in this list\n";
  for (const auto& p : world.objects) out << fmt::format("  - [{}, {}]\n", p.x(), p.y());
  out.flush();
  if (!out) throw WorldError(path + ": write failed");
}

}  // namespace neopipe::sim
