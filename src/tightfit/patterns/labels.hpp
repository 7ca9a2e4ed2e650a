#pragma once
/// Placement of the text drawn on pattern pieces (piece labels, seam names), in mm in
/// the piece's own plane (y up). A text's box is estimated from its character count
/// (sans-serif: advance ≈ kTextAdvance × height per character, descent 0.25 × height),
/// the same estimate for every writer, so that "inside the piece" can be checked.
#include <array>
#include <string>
#include <vector>

#include "tightfit/patterns/offset.hpp"

namespace tightfit {

/// Estimated mean advance of a character, in multiples of the text height.
inline constexpr double kTextAdvance = 0.62;
/// Smallest text height (mm) the labels shrink to before giving up on fitting.
inline constexpr double kMinTextHeightMm = 2.0;

/// A line of text to place: content and its preferred height (mm).
struct TextLine {
  std::string text;
  double height = 3.0;
  bool bold = false;
};

/// A placed text: the baseline starts at `at` and runs along the unit `direction`;
/// glyphs stand on the left of it (up = direction turned by +90°). mm, piece plane.
struct PlacedText {
  std::string text;
  Vec2 at = Vec2::Zero();
  Vec2 direction = Vec2::UnitX();
  double height = 3.0;
  bool bold = false;
};

/// Estimated length (mm) of `text` at `height` (UTF-8: one advance per code point).
double text_length(const std::string& text, double height);

/// The estimated box of a placed text: corners (mm) counter-clockwise, from the
/// baseline's start moved down by the descent.
std::array<Vec2, 4> text_box(const PlacedText& text);

/// Whether the box of `text` lies inside the closed polygon `polygon` (its corners and
/// edge midpoints inside, no polygon edge crossing the box edges).
bool text_inside(const PlacedText& text, const Polygon2& polygon);

/// Whether the box of `text` stays clear of the closed polygon `hole` (no corner or edge
/// midpoint inside it, no crossing, the hole not inside the box).
bool text_clear_of(const PlacedText& text, const Polygon2& hole);

/// Places `lines` as a left-aligned block, first line on top, horizontal (direction
/// +x), inside `polygon` (counter-clockwise) and clear of `holes`: the block is tried
/// right of and centred on `preferred` and then at interior grid points outside the
/// holes, farthest from the outline and the holes first;
/// at every spot the heights are scaled by 1, 0.9, 0.8, … down to the scale that makes
/// the smallest line kMinTextHeightMm high. The first spot and scale that fit win;
/// when none fits, the smallest scale at the interior point farthest from the outline.
std::vector<PlacedText> place_text_block(const Polygon2& polygon,
                                         const std::vector<TextLine>& lines, const Vec2& preferred,
                                         const std::vector<Polygon2>& holes = {});

/// Places one line along the polyline `side` (a part of the polygon's outline, ≥ 2
/// points): centred at the side's arc-length middle or, when `from_end_mm` ≥ 0, ending
/// `from_end_mm` before the side's last point (but not before its middle); parallel to
/// the side there, reading left to right (direction.x > 0; within about 11° of vertical:
/// bottom to top), with
/// its box `gap` mm inside the polygon. Its height shrinks from `height` (by 15 % steps)
/// to kMinTextHeightMm until text_inside(...) holds; the last try is returned.
PlacedText place_along_side(const Polygon2& polygon, const std::vector<Vec2>& side,
                            const std::string& text, double height, double gap,
                            double from_end_mm = -1.0);

}  // namespace tightfit
