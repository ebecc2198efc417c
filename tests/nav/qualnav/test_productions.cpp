// The heading productions (spec qualnav.md §5): all 96 cells against the spec's table transcribed
// here as text, the multi-landmark order, bad specifiers.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "nav/qualnav/topology/productions.hpp"

namespace {
namespace qn = neopipe::nav::qualnav;
constexpr double kDeg = std::numbers::pi / 180;

// Spec qualnav.md §5, copied cell by cell (the rebuilt Fig. 6 of seed 003).
const char* const kSpecTable = R"(| A,B | C,D | ABCD | ACBD | ACDB | CABD | CDAB | CADB |
|---|---|---|---|---|---|---|---|
| r | r | r[CD] | r[BD] | r[DB] | r[BD] | r[AB] | r[DB] |
| r | l | b[BC] | – | – | – | – | – |
| r | b | b[CD] | b[BD] | – | b[BD] | – | – |
| r | a | a[CC] | – | – | – | – | – |
| l | r | – | – | – | – | b[DA] | – |
| l | l | l[AB] | l[AC] | l[AC] | l[CA] | l[CD] | l[CA] |
| l | b | – | – | – | b[CA] | b[CD] | b[CA] |
| l | a | – | – | – | – | a[CC] | – |
| b | r | – | – | b[DB] | – | b[AB] | b[DB] |
| b | l | b[AB] | b[AC] | b[AC] | – | – | – |
| b | b | – | b[CB] | b[CD] | b[AB] | – | b[AD] |
| b | a | – | – | a[CC] | – | – | – |
| a | r | – | – | – | – | a[AA] | – |
| a | l | a[AA] | – | – | – | – | – |
| a | b | – | – | – | a[AA] | – | – |
| a | a | – | – | – | – | – | – |
)";

std::vector<std::string> cells_of(const std::string& row) {
  std::vector<std::string> cells;
  std::stringstream in(row);
  std::string cell;
  std::getline(in, cell, '|');  // before the first bar
  while (std::getline(in, cell, '|')) {
    const auto first = cell.find_first_not_of(' ');
    if (first == std::string::npos) continue;
    cells.push_back(cell.substr(first, cell.find_last_not_of(' ') - first + 1));
  }
  return cells;
}

}  // namespace

TEST(QualnavProductions, EveryCellEqualsTheSpecTable) {
  std::map<std::string, std::string> spec;  // "x y ORDER" -> production
  std::stringstream in(kSpecTable);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = cells_of(line);
  ASSERT_EQ(header.size(), 8U);
  std::getline(in, line);  // |---|
  while (std::getline(in, line)) {
    const std::vector<std::string> row = cells_of(line);
    ASSERT_EQ(row.size(), 8U) << line;
    for (std::size_t c = 2; c < 8; ++c) spec[row[0] + " " + row[1] + " " + header[c]] = row[c];
  }
  ASSERT_EQ(spec.size(), 96U);
  const std::vector<qn::ProductionCell> table = qn::production_table();
  ASSERT_EQ(table.size(), 96U);
  int dashes = 0;
  for (const qn::ProductionCell& cell : table) {
    const std::string key =
        std::string{qn::specifier_letter(cell.x)} + " " + qn::specifier_letter(cell.y) + " " + cell.order;
    ASSERT_TRUE(spec.contains(key)) << key;
    EXPECT_EQ(cell.production, spec[key]) << key;
    dashes += cell.production == qn::kNoProduction;
  }
  EXPECT_EQ(dashes, 96 - 36);  // 36 productions in the table
}

TEST(QualnavProductions, CommutesAndNamesWithRealIds) {
  const std::vector<qn::LandmarkId> order{7, 3, 9, 4};  // left to right
  const qn::HeadingSpecifier r73{qn::Specifier::r, 7, 3};
  const qn::HeadingSpecifier l94{qn::Specifier::l, 9, 4};
  const auto p = qn::produce(r73, l94, order);
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, (qn::HeadingSpecifier{qn::Specifier::b, 3, 9}));
  EXPECT_EQ(qn::produce(l94, r73, order), p);
  const std::vector<qn::HeadingSpecifier> three{r73, l94, {qn::Specifier::b, 7, 4}};
  EXPECT_EQ(qn::produce_all(three, order), p);
  EXPECT_EQ(qn::produce_all(std::span(three).first(1), order), r73);
}

TEST(QualnavProductions, BadSpecifiersAreNamed) {
  const std::vector<qn::LandmarkId> order{0, 1, 2};
  try {
    (void)qn::produce({qn::Specifier::b, 1, 0}, {qn::Specifier::l, 1, 2}, order);
    FAIL() << "a pair named right to left";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("b[1 0]"), std::string::npos) << e.what();
  }
  try {
    (void)qn::produce({qn::Specifier::b, 0, 5}, {qn::Specifier::l, 1, 2}, order);
    FAIL() << "a landmark not in view";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("landmark 5"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)qn::produce_all({}, order), std::invalid_argument);
}

// More landmarks than the table's four: the panorama is cut in the middle of its widest gap, and
// the order is left to right for an observer facing that gap's opposite.
TEST(QualnavProductions, MultiLandmarkOrderCutsTheWidestGap) {
  // Bearings 100°, 80°, 60°, 10° (counter-clockwise): facing north-ish, 100° is leftmost.
  const std::vector<qn::Sighting> seen{{4, 60 * kDeg}, {1, 100 * kDeg}, {2, 10 * kDeg}, {3, 80 * kDeg}};
  const auto order = qn::left_to_right_order(seen);
  ASSERT_TRUE(order);
  EXPECT_EQ(*order, (std::vector<qn::LandmarkId>{1, 3, 4, 2}));
  // The widest gap wraps through 0°: bearings 350°, 20°, 300° -> left to right 20°, 350°, 300°.
  const std::vector<qn::Sighting> wrap{{0, 350 * kDeg}, {1, 20 * kDeg}, {2, -60 * kDeg}};
  EXPECT_EQ(*qn::left_to_right_order(wrap), (std::vector<qn::LandmarkId>{1, 0, 2}));
  // Spread round the panorama: the widest gap is 150° < 180°, so the productions are undefined.
  const std::vector<qn::Sighting> around{{0, 0}, {1, 150 * kDeg}, {2, 240 * kDeg}};
  EXPECT_FALSE(qn::left_to_right_order(around));
  const std::vector<qn::Sighting> twice{{0, 0}, {0, 1}};
  EXPECT_THROW((void)qn::left_to_right_order(twice), std::invalid_argument);
  EXPECT_TRUE(qn::left_to_right_order({})->empty());
}

// [P Q] with P left of Q is the LPB side [P Q] of §4: the order puts first the landmark whose pair
// orientation (first, second) is +1, for any two bearings less than 180° apart.
TEST(QualnavProductions, LeftOfIsOrientationPlusOne) {
  for (int i = 0; i < 3600; ++i) {
    const double b1 = i * 0.1 * kDeg;
    const double b2 = b1 + (7 + (i * 37) % 706) * 0.5 * kDeg;  // 3.5° to 356° counter-clockwise of b1
    if (std::abs(std::abs(std::remainder(b1 - b2, 2 * std::numbers::pi)) - std::numbers::pi) < 1e-9) continue;
    const std::vector<qn::Sighting> seen{{0, b1}, {1, b2}};
    const auto order = qn::left_to_right_order(seen);
    ASSERT_TRUE(order);
    const int o = qn::orientation_from_bearings(b1, b2);
    EXPECT_EQ(order->front(), o > 0 ? 0U : 1U) << b1 / kDeg << " " << b2 / kDeg;
  }
}
