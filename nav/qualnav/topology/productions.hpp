#pragma once
// Heading productions (spec qualnav.md §5, seed 003 Fig. 6 rebuilt). A heading specifier x[P Q] over
// a pair seen with P left of Q names an interval of the view's left-to-right order of landmarks:
// l = (left end, P), b = (P, Q), r = (Q, right end), a = the point P. The production of two
// specifiers is the intersection of their intervals, named again as a specifier, or "–" when empty.
// Views with more than the four landmarks of the table are ordered by cutting the panorama at the
// middle of its widest empty gap (a Decision of the spec); below 180° the order is undefined.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "nav/qualnav/topology/lpb.hpp"

namespace neopipe::nav::qualnav {

enum class Specifier : std::uint8_t {
  l,  ///< pass left of P (cross the LPB beyond P)
  b,  ///< pass between P and Q
  r,  ///< pass right of Q (cross the LPB beyond Q)
  a   ///< head to P
};

/// 'l', 'b', 'r' or 'a'.
char specifier_letter(Specifier s);

/// x[P Q]: P left of Q in the view. a[P P] (both P) is the production "head to P".
struct HeadingSpecifier {
  Specifier kind = Specifier::b;
  LandmarkId left = 0;   ///< P
  LandmarkId right = 0;  ///< Q
  friend bool operator==(const HeadingSpecifier&, const HeadingSpecifier&) = default;
};

/// The production "–": no heading satisfies both specifiers.
inline constexpr std::string_view kNoProduction = "–";

/// The production of x and y over `left_to_right` (every landmark of the view, left first):
/// std::nullopt for "–". std::invalid_argument if a specifier names a landmark not in the order, or
/// names its pair right to left (an a may name P twice).
std::optional<HeadingSpecifier> produce(const HeadingSpecifier& x, const HeadingSpecifier& y,
                                        std::span<const LandmarkId> left_to_right);

/// The production of a conjunction, reduced two at a time from the left; std::nullopt for "–".
/// An empty conjunction is std::invalid_argument.
std::optional<HeadingSpecifier> produce_all(std::span<const HeadingSpecifier> conjunction,
                                            std::span<const LandmarkId> left_to_right);

/// The view's left-to-right order: the sightings clockwise (pan order), starting just clockwise of
/// the middle of the widest gap between consecutive bearings. std::nullopt when that gap is below
/// 180° (the productions are undefined there; fall back to viewframe headings). Repeated ids are
/// std::invalid_argument.
std::optional<std::vector<LandmarkId>> left_to_right_order(std::span<const Sighting> seen);

/// One cell of the table of §5: x[A B] and y[C D] in a view ordered `order` (e.g. "ACBD"), its
/// production written with the letters A..D ("r[BD]", "a[CC]" or "–").
struct ProductionCell {
  Specifier x = Specifier::l;
  Specifier y = Specifier::l;
  std::string order;
  std::string production;
};

/// The six orders of A, B, C, D with A left of B and C left of D, in the spec's column order:
/// ABCD ACBD ACDB CABD CDAB CADB.
std::span<const std::string_view> production_orders();

/// The four specifiers in the spec's row order: r, l, b, a.
std::span<const Specifier> production_row_order();

/// All 96 cells (16 rows x, y in the spec's order, 6 columns each), computed by produce().
std::vector<ProductionCell> production_table();

}  // namespace neopipe::nav::qualnav
