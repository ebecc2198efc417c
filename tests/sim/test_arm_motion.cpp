// The motion error model: over 10,000 moves with a fixed seed, the errors along and across the
// commanded direction and of the heading, each divided by the sigma the model gives for that move,
// must look like N(0, 1): mean, standard deviation and a Kolmogorov-Smirnov test. The tolerances
// sit about four standard errors out, so no seed is likely to fail them (about 1 in 10^4), while a
// sigma wrong by 10% moves the standard deviation fourteen standard errors: a test below proves the
// same check rejects it. Also: sigma at fixed distances and turns, the axes of the errors, zero
// errors, and validation.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "sim/arm/motion_model.hpp"
#include "sim/arm/simulated_arm.hpp"

namespace neopipe::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kMoves = 10000;
constexpr std::uint64_t kSeed = 20240611;

struct NormalFit {
  double mean = 0;
  double sd = 0;
  double ks = 0;  ///< Kolmogorov-Smirnov statistic against N(0, 1)
};

NormalFit fit_standard_normal(std::vector<double> z) {
  NormalFit f;
  const double n = static_cast<double>(z.size());
  for (const double v : z) f.mean += v / n;
  for (const double v : z) f.sd += (v - f.mean) * (v - f.mean) / (n - 1);
  f.sd = std::sqrt(f.sd);
  std::sort(z.begin(), z.end());
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double cdf = 0.5 * std::erfc(-z[i] / std::numbers::sqrt2);
    f.ks = std::max({f.ks, cdf - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - cdf});
  }
  return f;
}

/// N(0, 1) at 10,000 samples: mean within 4 standard errors (0.01 each), sd within 0.03 (4.2 standard
/// errors of 0.007), KS statistic below its 0.1% critical value 1.95 / sqrt(n).
testing::AssertionResult looks_standard_normal(const NormalFit& f) {
  const double ks_critical = 1.95 / std::sqrt(static_cast<double>(kMoves));
  if (std::abs(f.mean) < 0.04 && std::abs(f.sd - 1) < 0.03 && f.ks < ks_critical) return testing::AssertionSuccess();
  return testing::AssertionFailure() << "mean " << f.mean << ", sd " << f.sd << ", KS " << f.ks << " (critical "
                                     << ks_critical << ")";
}

std::vector<double> scaled(std::vector<double> v, double factor) {
  for (double& x : v) x *= factor;
  return v;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double sab = 0;
  double saa = 0;
  double sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += a[i] * b[i];
    saa += a[i] * a[i];
    sbb += b[i] * b[i];
  }
  return sab / std::sqrt(saa * sbb);
}

/// Errors of kMoves moves made by a SimulatedArm, each divided by the sigma the model gives for it.
struct NormalisedErrors {
  std::vector<double> along;
  std::vector<double> across;
  std::vector<double> heading;
};

/// Each move starts from an exact placement (random position near the centre, random heading) and
/// is a random translation of 0..150 mm in a random direction with a random turn of -90..90 deg. The
/// commands come from their own stream, so the arm's error stream is the only one the seed drives.
NormalisedErrors sample_moves(const MotionErrors& errors, std::uint64_t seed) {
  SimulatedArm arm(ScaraGeometry{}, errors, seed, {250, 250, 0});
  Random commands(seed ^ 0x5DEECE66DULL);
  NormalisedErrors out;
  for (int i = 0; i < kMoves; ++i) {
    const Pose2 start{commands.uniform(150, 350), commands.uniform(150, 350), commands.uniform(-kPi, kPi)};
    arm.move_to(start);
    const double distance = commands.uniform(0, 150);
    const double direction = commands.uniform(-kPi, kPi);
    const double turn = commands.uniform(-kPi / 2, kPi / 2);
    const double dx = distance * std::cos(direction);
    const double dy = distance * std::sin(direction);
    arm.move_relative(dx, dy, turn);
    const Pose2 nominal = compose(start, dx, dy, turn);
    // The position error in the start tool frame, then along and across the commanded direction.
    const double wx = arm.pose().x - nominal.x;
    const double wy = arm.pose().y - nominal.y;
    const double ex = std::cos(start.theta) * wx + std::sin(start.theta) * wy;
    const double ey = -std::sin(start.theta) * wx + std::cos(start.theta) * wy;
    const double d = std::hypot(dx, dy);
    const double ux = dx / d;
    const double uy = dy / d;
    out.along.push_back((ex * ux + ey * uy) / errors.along_sigma(d));
    out.across.push_back((-ex * uy + ey * ux) / errors.across_sigma(d));
    out.heading.push_back((arm.pose().theta - nominal.theta) / errors.rotation_sigma(d, turn));
  }
  return out;
}

void print_fit(const char* what, const NormalFit& f) {
  std::printf("[ measured ] %-32s mean %+.4f  sd %.4f  KS %.4f\n", what, f.mean, f.sd, f.ks);
}

TEST(ArmMotionStatistics, ErrorsFollowTheirDistributionsOverTenThousandMoves) {
  const NormalisedErrors e = sample_moves(MotionErrors{}, kSeed);
  const NormalFit along = fit_standard_normal(e.along);
  const NormalFit across = fit_standard_normal(e.across);
  const NormalFit heading = fit_standard_normal(e.heading);
  print_fit("along / sigma_along", along);
  print_fit("across / sigma_across", across);
  print_fit("heading / sigma_theta", heading);
  EXPECT_TRUE(looks_standard_normal(along)) << "along";
  EXPECT_TRUE(looks_standard_normal(across)) << "across";
  EXPECT_TRUE(looks_standard_normal(heading)) << "heading";
  // Independent errors: correlations within 4 standard errors (0.01) of zero.
  EXPECT_LT(std::abs(correlation(e.along, e.across)), 0.04);
  EXPECT_LT(std::abs(correlation(e.along, e.heading)), 0.04);
  EXPECT_LT(std::abs(correlation(e.across, e.heading)), 0.04);
}

TEST(ArmMotionStatistics, TheSameCheckRejectsASigmaWrongByTenPercent) {
  const NormalisedErrors e = sample_moves(MotionErrors{}, kSeed);
  const struct {
    const char* name;
    const std::vector<double>& samples;
  } axes[] = {{"along", e.along}, {"across", e.across}, {"heading", e.heading}};
  for (const auto& axis : axes) {
    ASSERT_TRUE(looks_standard_normal(fit_standard_normal(axis.samples)));
    const NormalFit too_small = fit_standard_normal(scaled(axis.samples, 1 / 1.1));  // as if drawn 10% too small
    const NormalFit too_large = fit_standard_normal(scaled(axis.samples, 1 / 0.9));  // as if drawn 10% too large
    print_fit((std::string(axis.name) + ", drawn 10% small").c_str(), too_small);
    print_fit((std::string(axis.name) + ", drawn 10% large").c_str(), too_large);
    EXPECT_FALSE(looks_standard_normal(too_small)) << axis.name;
    EXPECT_FALSE(looks_standard_normal(too_large)) << axis.name;
  }
}

TEST(ArmMotionStatistics, OtherSeedsAndCoefficientsFitToo) {
  MotionErrors errors;
  errors.translation_sigma0 = 0.2;
  errors.along_per_mm = 0.01;
  errors.across_per_mm = 0.001;
  errors.rotation_sigma0 = radians(0.01);
  errors.rotation_per_mm = radians(0.01);
  errors.rotation_per_rad = 0.05;
  for (const std::uint64_t seed : {1ULL, 2ULL, 3ULL}) {
    const NormalisedErrors e = sample_moves(errors, seed);
    EXPECT_TRUE(looks_standard_normal(fit_standard_normal(e.along))) << "seed " << seed;
    EXPECT_TRUE(looks_standard_normal(fit_standard_normal(e.across))) << "seed " << seed;
    EXPECT_TRUE(looks_standard_normal(fit_standard_normal(e.heading))) << "seed " << seed;
  }
}

/// Standard deviations of the raw errors of kMoves perturbations of one command.
struct RawSpread {
  double along = 0;
  double across = 0;
  double heading = 0;
};

RawSpread spread_of(const MotionErrors& errors, const ToolMove& command, std::uint64_t seed) {
  Random random(seed);
  const double d = std::hypot(command.dx, command.dy);
  const double ux = d > 0 ? command.dx / d : 1;
  const double uy = d > 0 ? command.dy / d : 0;
  std::vector<double> along;
  std::vector<double> across;
  std::vector<double> heading;
  for (int i = 0; i < kMoves; ++i) {
    const ToolMove m = perturb(errors, command, random);
    const double ex = m.dx - command.dx;
    const double ey = m.dy - command.dy;
    along.push_back(ex * ux + ey * uy);
    across.push_back(-ex * uy + ey * ux);
    heading.push_back(m.dtheta - command.dtheta);
  }
  return {fit_standard_normal(along).sd, fit_standard_normal(across).sd, fit_standard_normal(heading).sd};
}

TEST(ArmMotionStatistics, SigmaGrowsWithDistanceAndTurnAsConfigured) {
  const MotionErrors errors;  // defaults: 0.05 mm + 0.003 d; 0.05 deg + 0.002 deg/mm d + 0.005 |turn|
  struct Case {
    ToolMove command;
    double along_mm;
    double across_mm;
    double heading_deg;
  };
  const Case cases[] = {
      {{0, 0, 0}, 0.05, 0.05, 0.05},                       // standing still: the repeatability floor
      {{100, 0, 0}, 0.35, 0.35, 0.25},                     // 100 mm East in the tool frame
      {{0, -200, 0}, 0.65, 0.65, 0.45},                    // 200 mm along the tool's -y axis
      {{0, 0, radians(90)}, 0.05, 0.05, 0.05 + 0.45},      // a quarter turn in place
      {{60, 80, radians(-45)}, 0.35, 0.35, 0.25 + 0.225},  // 100 mm diagonally and an eighth turn right
  };
  std::uint64_t seed = 100;
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << "move (" << c.command.dx << ", " << c.command.dy << ", "
                                    << degrees(c.command.dtheta) << " deg)");
    const RawSpread s = spread_of(errors, c.command, seed++);
    std::printf(
        "[ measured ] move (%g, %g, %g deg): sd along %.4f (%.4f), across %.4f (%.4f), heading %.4f (%.4f) deg\n",
        c.command.dx, c.command.dy, degrees(c.command.dtheta), s.along, c.along_mm, s.across, c.across_mm,
        degrees(s.heading), c.heading_deg);
    EXPECT_NEAR(s.along / c.along_mm, 1, 0.03);
    EXPECT_NEAR(s.across / c.across_mm, 1, 0.03);
    EXPECT_NEAR(degrees(s.heading) / c.heading_deg, 1, 0.03);
  }
}

TEST(ArmMotion, ErrorsLieAlongAndAcrossTheCommandedDirection) {
  MotionErrors only_along = MotionErrors::none();
  only_along.along_per_mm = 0.01;
  Random random(5);
  for (int i = 0; i < 100; ++i) {
    const ToolMove m = perturb(only_along, {0, 100, 0}, random);  // along the tool's y axis
    EXPECT_EQ(m.dx, 0);
    EXPECT_NE(m.dy, 100);
    EXPECT_EQ(m.dtheta, 0);
  }
  MotionErrors only_across = MotionErrors::none();
  only_across.across_per_mm = 0.01;
  for (int i = 0; i < 100; ++i) {
    const ToolMove m = perturb(only_across, {0, 100, 0}, random);
    EXPECT_NE(m.dx, 0);
    EXPECT_EQ(m.dy, 100);
  }
}

TEST(ArmMotion, ZeroErrorsGiveTheCommandedMoveExactlyAndStillDrawThreeNumbers) {
  Random random(9);
  Random reference(9);
  for (const ToolMove c : {ToolMove{12.5, -3, 0.25}, ToolMove{0, 0, 0}, ToolMove{-100, 40, -3}}) {
    const ToolMove m = perturb(MotionErrors::none(), c, random);
    EXPECT_EQ(m.dx, c.dx);
    EXPECT_EQ(m.dy, c.dy);
    EXPECT_EQ(m.dtheta, c.dtheta);
    for (int k = 0; k < 3; ++k) reference.normal();
  }
  EXPECT_EQ(random.next(), reference.next());
}

TEST(ArmMotion, ADifferentSigmaDoesNotShiftTheOtherErrors) {
  MotionErrors a;
  MotionErrors b = a;
  b.rotation_per_rad = 0.2;
  Random ra(3);
  Random rb(3);
  for (int i = 0; i < 100; ++i) {
    const ToolMove ma = perturb(a, {30, 40, 1}, ra);
    const ToolMove mb = perturb(b, {30, 40, 1}, rb);
    EXPECT_EQ(ma.dx, mb.dx);
    EXPECT_EQ(ma.dy, mb.dy);
    EXPECT_NE(ma.dtheta, mb.dtheta);
  }
}

TEST(ArmMotion, NegativeOrNonFiniteCoefficientsAreRejectedByName) {
  MotionErrors e;
  EXPECT_NO_THROW(validate(e));
  EXPECT_NO_THROW(validate(MotionErrors::none()));
  e.across_per_mm = -0.001;
  try {
    validate(e);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& x) {
    EXPECT_NE(std::string(x.what()).find("across_per_mm"), std::string::npos) << x.what();
  }
  e = {};
  e.rotation_sigma0 = std::nan("");
  EXPECT_THROW(validate(e), std::invalid_argument);
  EXPECT_THROW(SimulatedArm(ScaraGeometry{}, e, 1, {250, 250, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace neopipe::sim
