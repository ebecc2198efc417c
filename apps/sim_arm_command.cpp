#include "apps/sim_arm_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

#include "apps/cli_support.hpp"
#include "sim/arm/moves_csv.hpp"
#include "sim/arm/scara_sizing.hpp"
#include "sim/arm/simulated_arm.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

constexpr const char* kReportHeader =
    "move,dx,dy,dtheta,cmd_x,cmd_y,cmd_theta,x,y,theta,err_x,err_y,err_theta,shoulder,elbow,roll";

/// `count` comma-separated finite numbers, or a UsageError naming the option and the expected form.
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& option,
                                  const std::string& form) {
  std::vector<double> values;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = text.find(',', begin);
    std::istringstream field(text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    double v = 0;
    if (!(field >> v) || !(field >> std::ws).eof() || !std::isfinite(v)) {
      throw UsageError{fmt::format("{} {}: expected {}", option, text, form)};
    }
    values.push_back(v);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  if (values.size() != count) throw UsageError{option + " " + text + ": expected " + form};
  return values;
}

sim::ScaraGeometry arm_geometry(const SimArmArgs& a, const Eigen::Vector2d& workspace) {
  sim::ScaraGeometry g = sim::scara_for_workspace(workspace);
  if (!a.base.empty()) {
    const auto b = parse_numbers(a.base, 2, "--base", "X,Y in mm, e.g. 250,-125");
    g.base = {b[0], b[1]};
  }
  if (!a.links.empty()) {
    const auto l = parse_numbers(a.links, 2, "--links", "L1,L2 in mm, e.g. 375,375");
    g.l1 = l[0];
    g.l2 = l[1];
  }
  return g;
}

sim::MotionErrors motion_errors(const SimArmErrorArgs& e) {
  if (e.none) return sim::MotionErrors::none();
  return {e.sigma0,     e.along_per_mm, e.across_per_mm, sim::radians(e.rot_sigma0_deg), sim::radians(e.rot_per_mm_deg),
          e.rot_per_deg};
}

sim::Pose2 start_pose(const SimArmArgs& a, const Eigen::Vector2d& workspace) {
  if (a.start.empty()) return {workspace.x() / 2, workspace.y() / 2, 0};
  const auto s = parse_numbers(a.start, 3, "--start", "X,Y,THETA in mm, mm, degrees, e.g. 250,250,0");
  return {s[0], s[1], sim::radians(s[2])};
}

sim::SimulatedArm make_arm(const SimArmArgs& a, const sim::World& world) {
  const sim::ScaraGeometry geometry = arm_geometry(a, world.size);
  const sim::Pose2 start = start_pose(a, world.size);
  try {
    // NOLINTNEXTLINE(modernize-return-braced-init-list): the constructor is explicit
    return sim::SimulatedArm(geometry, motion_errors(a.errors), a.seed, start);
  } catch (const sim::ReachError& e) {
    throw sim::ReachError(fmt::format("--start {}: {}", a.start.empty() ? "(workspace centre)" : a.start, e.what()));
  }
}

/// A sigma coefficient: a finite number >= 0 (CLI::NonNegativeNumber would print the whole of DBL_MAX).
CLI::Validator non_negative() {
  return CLI::Validator(  // NOLINT(modernize-return-braced-init-list): two constructors take these
      [](const std::string& text) {
        double v = 0;
        if (CLI::detail::lexical_cast(text, v) && std::isfinite(v) && v >= 0) return std::string();
        return "expected a number >= 0, not " + text;
      },
      "");
}

/// Six decimals (a micrometre, a micro-degree); never "-0.000000", which would only be rounding noise.
std::string fixed(double v) {
  std::string s = fmt::format("{:.6f}", v);
  if (s == "-0.000000") s.erase(0, 1);
  return s;
}

void write_row(std::ostream& out, int move, const sim::MoveLine& command, const sim::SimulatedArm& arm) {
  const sim::Pose2& c = arm.commanded_pose();
  const sim::Pose2& p = arm.pose();
  const sim::JointAngles& q = arm.joints();
  out << move << ',' << fixed(command.dx) << ',' << fixed(command.dy) << ',' << fixed(command.dtheta_deg) << ','
      << fixed(c.x) << ',' << fixed(c.y) << ',' << fixed(sim::degrees(c.theta)) << ',' << fixed(p.x) << ','
      << fixed(p.y) << ',' << fixed(sim::degrees(p.theta)) << ',' << fixed(p.x - c.x) << ',' << fixed(p.y - c.y) << ','
      << fixed(sim::degrees(p.theta - c.theta)) << ',' << fixed(sim::degrees(q.shoulder)) << ','
      << fixed(sim::degrees(q.elbow)) << ',' << fixed(sim::degrees(q.roll)) << '\n';
}

struct DriveSummary {
  int moves = 0;
  double largest_error = 0;  ///< mm, truth - commanded
  int largest_at = 0;        ///< the move after which it was seen
};

/// Writes the report: the start, then a row per move as soon as it is made, so that a bad line or an
/// unreachable move further on (thrown as "<moves file>:<line>: ...") leaves the rows before it.
DriveSummary drive(sim::SimulatedArm& arm, sim::MovesReader& moves, std::ostream& out) {
  out << kReportHeader << '\n';
  write_row(out, 0, {}, arm);
  DriveSummary summary;
  while (const auto m = moves.next()) {
    try {
      arm.move_relative(m->dx, m->dy, sim::radians(m->dtheta_deg));
    } catch (const sim::ReachError& e) {
      throw sim::ReachError(fmt::format("{}:{}: {}", moves.path(), m->line, e.what()));
    }
    write_row(out, ++summary.moves, *m, arm);
    const double error = std::hypot(arm.pose().x - arm.commanded_pose().x, arm.pose().y - arm.commanded_pose().y);
    if (error > summary.largest_error) {
      summary.largest_error = error;
      summary.largest_at = summary.moves;
    }
  }
  return summary;
}

void print_summary(const SimArmArgs& a, const sim::SimulatedArm& arm, const DriveSummary& s) {
  const sim::Scara& k = arm.kinematics();
  const sim::Pose2& p = arm.pose();
  const sim::Pose2& c = arm.commanded_pose();
  std::cerr << fmt::format(
      "neopipe sim arm: base ({}, {}) mm, links {} + {} mm, reach {:.2f}..{:.2f} mm; {} moves (seed {}){}\n"
      "  final pose ({:.3f}, {:.3f}, {:.3f} deg), commanded ({:.3f}, {:.3f}, {:.3f} deg): error {:.3f} mm, "
      "{:.3f} deg; largest position error {:.3f} mm after move {}\n",
      k.geometry().base.x(), k.geometry().base.y(), k.geometry().l1, k.geometry().l2, k.min_reach(), k.max_reach(),
      s.moves, a.seed, a.out.empty() ? "" : " -> " + a.out, p.x, p.y, sim::degrees(p.theta), c.x, c.y,
      sim::degrees(c.theta), std::hypot(p.x - c.x, p.y - c.y), sim::degrees(p.theta - c.theta), s.largest_error,
      s.largest_at);
}

}  // namespace

void add_sim_arm_options(CLI::App& cmd, SimArmArgs& a) {
  cmd.footer(
      "Moves file: CSV with the header dx,dy,dtheta, then one move per line: dx, dy in mm along the tool frame's\n"
      "x and y axes at the start of the move, then a turn of dtheta degrees counter-clockwise.\n"
      "Report: " +
      std::string(kReportHeader) +
      "\n"
      "  row 0 is the start; cmd_* = where the commands alone lead (dead reckoning), x,y,theta = ground truth,\n"
      "  err_* = truth - commanded in world axes; lengths in mm, angles in degrees (theta not wrapped).\n"
      "Errors per move of length d mm and turn t: Gaussian along and across the commanded direction,\n"
      "  sigma = sigma0 + along|across-per-mm * d; heading: sigma = rot-sigma0 + rot-per-mm * d + rot-per-deg * |t|.\n"
      "Exit status: 0 done, 1 bad input or an unreachable pose (rows of the moves made are kept), 2 bad command line.");
  cmd.add_option("--world", a.world, "World file (YAML); its size sets the arm's workspace")
      ->required()
      ->type_name("W.yaml");
  cmd.add_option("--moves", a.moves, "Moves file (CSV: dx,dy,dtheta in mm, mm, degrees)")
      ->required()
      ->type_name("M.csv");
  cmd.add_option("--out", a.out, "Write the report here instead of stdout")->type_name("R.csv");
  cmd.add_option("--seed", a.seed, "Random seed: the same seed gives the same motion errors")->capture_default_str();
  cmd.add_option("--start", a.start, "Start pose (mm, mm, degrees); default: the workspace centre, heading 0")
      ->type_name("X,Y,THETA");
  cmd.add_option("--base", a.base, "Arm base (shoulder axis) position, mm; default: sized for the workspace")
      ->type_name("X,Y");
  cmd.add_option("--links", a.links, "Link lengths l1 (upper arm), l2 (forearm), mm; default: sized for the workspace")
      ->type_name("L1,L2");

  SimArmErrorArgs& e = a.errors;
  CLI::Option* none = cmd.add_flag("--no-errors", e.none, "Move exactly as commanded (all error sigmas 0)");
  const auto coefficient = [&](const char* name, double& value, const char* unit, const char* help) {
    cmd.add_option(name, value, help)
        ->check(non_negative())
        ->type_name(unit)
        ->default_str(fmt::format("{:g}", value))
        ->excludes(none);
  };
  coefficient("--sigma0", e.sigma0, "MM", "Translation error sigma of every move, mm");
  coefficient("--along-per-mm", e.along_per_mm, "MM/MM", "Translation error sigma along the move, mm per mm moved");
  coefficient("--across-per-mm", e.across_per_mm, "MM/MM", "Translation error sigma across the move, mm per mm moved");
  coefficient("--rot-sigma0", e.rot_sigma0_deg, "DEG", "Heading error sigma of every move, degrees");
  coefficient("--rot-per-mm", e.rot_per_mm_deg, "DEG/MM", "Heading error sigma, degrees per mm moved");
  coefficient("--rot-per-deg", e.rot_per_deg, "DEG/DEG", "Heading error sigma, degrees per degree turned");
}

int sim_arm_command(const SimArmArgs& a) {
  sim::SimulatedArm arm = make_arm(a, sim::load_world(a.world));
  sim::MovesReader moves(a.moves);
  std::ofstream file;
  if (!a.out.empty()) {
    file.open(a.out, std::ios::trunc);
    if (!file) throw std::runtime_error(a.out + ": cannot be written");
  }
  std::ostream& out = a.out.empty() ? std::cout : file;
  const DriveSummary summary = drive(arm, moves, out);
  out.flush();
  if (!out) throw std::runtime_error((a.out.empty() ? std::string("stdout") : a.out) + ": write failed");
  print_summary(a, arm, summary);
  return kExitOk;
}

}  // namespace neopipe::apps
