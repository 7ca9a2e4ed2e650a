#include "tightfit/patterns/svg.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "patterns/support/pattern_fixtures.hpp"
#include "patterns/support/pattern_tools.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/layout.hpp"

namespace tightfit::pattern_svg_test {

using test::run_command;
using test::shell_quote;

const char* const kRsvg = "/usr/bin/rsvg-convert";

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(PatternSvg, RootSizedInMillimetresWithOneGroupPerPiece) {
  const auto dir = test::scratch_dir("svg_structure");
  const auto file = dir / "pattern.svg";
  const Pattern pattern = test::test_pattern();
  write_pattern_svg(pattern, {}, file);
  const std::string svg = read_text(file);
  const auto pieces = draw_pattern_pieces(pattern, {}, "test");
  const PatternLayout layout = layout_pattern(pieces, {});
  const std::string root =
      svg.substr(svg.find("<svg "), svg.find('>', svg.find("<svg ")) - svg.find("<svg "));
  double width = 0.0;
  double height = 0.0;
  double box[4] = {-1.0, -1.0, -1.0, -1.0};
  const auto attribute = [&](const std::string& name) {
    const size_t at = root.find(" " + name + "=\"");
    EXPECT_NE(at, std::string::npos) << name;
    return at == std::string::npos ? std::string() : root.substr(at + name.size() + 3);
  };
  ASSERT_EQ(std::sscanf(attribute("width").c_str(), "%lfmm\"", &width), 1);
  ASSERT_EQ(std::sscanf(attribute("height").c_str(), "%lfmm\"", &height), 1);
  ASSERT_EQ(std::sscanf(attribute("viewBox").c_str(), "%lf %lf %lf %lf", &box[0], &box[1], &box[2],
                        &box[3]),
            4);
  EXPECT_NE(attribute("width").find("mm\""), std::string::npos);
  EXPECT_NEAR(width, layout.width_mm, 1e-3);
  EXPECT_NEAR(height, layout.height_mm, 1e-3);
  EXPECT_EQ(box[0], 0.0);
  EXPECT_EQ(box[1], 0.0);
  EXPECT_EQ(box[2], width);
  EXPECT_EQ(box[3], height);
  for (const std::string id : {"piece-front", "piece-back", "piece-sleeve", "test-square"}) {
    EXPECT_NE(svg.find("<g id=\"" + id + "\">"), std::string::npos) << id;
  }
  auto count = [&](const std::string& needle) {
    size_t n = 0;
    for (size_t at = svg.find(needle); at != std::string::npos; at = svg.find(needle, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("class=\"cut\""), 3u);
  EXPECT_EQ(count("class=\"sew\""), 3u);
  EXPECT_EQ(count("class=\"grain\""), 3u);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  size_t notches = 0;
  for (const auto& piece : pieces) notches += piece.notches.size();
  // Every notch and every grain shaft is one <line>.
  EXPECT_EQ(count("<line "), notches + pieces.size());
  EXPECT_EQ(count(">front</text>"), 1u);
}

TEST(PatternSvg, RsvgRendersTheTestSquareAtTrueSize) {
  test::require_program(kRsvg);
  const auto dir = test::scratch_dir("svg_render");
  const auto file = dir / "pattern.svg";
  const Pattern pattern = test::test_pattern();
  write_pattern_svg(pattern, {}, file);
  const auto render =
      run_command(std::string(kRsvg) + " --dpi-x 96 --dpi-y 96 -b white -f png -o " +
                  shell_quote(dir / "pattern.png") + " " + shell_quote(file));
  ASSERT_EQ(render.exit_code, 0) << render.output;
  const test::GrayImage image = test::read_png(dir / "pattern.png");
  const auto pieces = draw_pattern_pieces(pattern, {}, "test");
  const PatternLayout layout = layout_pattern(pieces, {});
  const double px_per_mm = 96.0 / 25.4;
  EXPECT_NEAR(image.width, layout.width_mm * px_per_mm, 1.0);
  EXPECT_NEAR(image.height, layout.height_mm * px_per_mm, 1.0);
  // The square's edges are 0.3 mm strokes centred on its sides: find the centre of
  // each stroke from the pixels of the row (column) through the square's middle,
  // searching ±3 mm around where the side should be, and away from the label text.
  const Box2& s = layout.test_square;
  const int row = static_cast<int>((s.min.y() + 0.8 * kTestSquareMm) * px_per_mm);
  const int col = static_cast<int>((s.min.x() + 0.8 * kTestSquareMm) * px_per_mm);
  const int window = static_cast<int>(3.0 * px_per_mm);
  const double left =
      test::ink_centre_x(image, row, static_cast<int>(s.min.x() * px_per_mm) - window,
                         static_cast<int>(s.min.x() * px_per_mm) + window);
  const double right =
      test::ink_centre_x(image, row, static_cast<int>(s.max.x() * px_per_mm) - window,
                         static_cast<int>(s.max.x() * px_per_mm) + window);
  const double top =
      test::ink_centre_y(image, col, static_cast<int>(s.min.y() * px_per_mm) - window,
                         static_cast<int>(s.min.y() * px_per_mm) + window);
  const double bottom =
      test::ink_centre_y(image, col, static_cast<int>(s.max.y() * px_per_mm) - window,
                         static_cast<int>(s.max.y() * px_per_mm) + window);
  const double expected = 100.0 * px_per_mm;  // 377.95 px
  RecordProperty("square_width_px", std::to_string(right - left));
  RecordProperty("square_height_px", std::to_string(bottom - top));
  EXPECT_NEAR(right - left, expected, 1.0);
  EXPECT_NEAR(bottom - top, expected, 1.0);
  // The front's cut line (300 mm + 2 × 10 mm wide) is where the layout puts it.
  const Box2& front = layout.piece_boxes[0];
  const int front_row = static_cast<int>((front.min.y() + 0.6 * front.height()) * px_per_mm);
  const double front_left =
      test::ink_centre_x(image, front_row, static_cast<int>(front.min.x() * px_per_mm) - window,
                         static_cast<int>(front.min.x() * px_per_mm) + window);
  const double front_right =
      test::ink_centre_x(image, front_row, static_cast<int>(front.max.x() * px_per_mm) - window,
                         static_cast<int>(front.max.x() * px_per_mm) + window);
  EXPECT_NEAR(front_right - front_left, 320.0 * px_per_mm, 1.0);
}

TEST(PatternSvg, InvalidPatternIsAnInputErrorAndLeavesNoFile) {
  const auto dir = test::scratch_dir("svg_invalid");
  Pattern pattern = test::test_pattern();
  pattern.seams[1].a.vertices.push_back(0);
  EXPECT_THROW(write_pattern_svg(pattern, {}, dir / "pattern.svg"), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace tightfit::pattern_svg_test
