#include "tightfit/patterns/pdf.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "patterns/support/pattern_fixtures.hpp"
#include "patterns/support/pattern_tools.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/layout.hpp"

namespace tightfit::pattern_pdf_test {

using test::run_command;
using test::shell_quote;

const char* const kPdfInfo = "/usr/bin/pdfinfo";
const char* const kPdfToPpm = "/usr/bin/pdftoppm";

struct PdfInfo {
  int pages = 0;
  double width_pt = 0.0;
  double height_pt = 0.0;
};

PdfInfo pdf_info(const std::filesystem::path& file) {
  const auto info = run_command(std::string(kPdfInfo) + " " + shell_quote(file));
  EXPECT_EQ(info.exit_code, 0) << info.output;
  PdfInfo out;
  std::istringstream lines(info.output);
  for (std::string line; std::getline(lines, line);) {
    std::sscanf(line.c_str(), "Pages: %d", &out.pages);
    std::sscanf(line.c_str(), "Page size: %lf x %lf pts", &out.width_pt, &out.height_pt);
  }
  return out;
}

/// A layout narrow enough to need several columns and rows of pages.
PatternExportOptions tiled_options(Paper paper) {
  PatternExportOptions options;
  options.paper = paper;
  options.layout_width = 0.5;
  return options;
}

/// Pages along one side of a layout, computed from the sizes alone.
int expected_tiles(double layout_mm, double page_mm, double margin_mm, double overlap_mm) {
  const double content = page_mm - 2.0 * margin_mm;
  return std::max(1,
                  static_cast<int>(std::ceil((layout_mm - overlap_mm) / (content - overlap_mm))));
}

void check_tiled(Paper paper, double page_w_pt, double page_h_pt, const std::string& name) {
  test::require_program(kPdfInfo);
  const auto dir = test::scratch_dir(name);
  const PatternExportOptions options = tiled_options(paper);
  const Pattern pattern = test::test_pattern();
  write_pattern_pdf_tiled(pattern, options, dir / "tiles.pdf");
  write_pattern_pdf_full_size(pattern, options, dir / "full.pdf");
  const PdfInfo tiles = pdf_info(dir / "tiles.pdf");
  const PdfInfo full = pdf_info(dir / "full.pdf");
  EXPECT_NEAR(tiles.width_pt, page_w_pt, 0.01);
  EXPECT_NEAR(tiles.height_pt, page_h_pt, 0.01);
  // The full-size page is the layout's bounding box.
  const PatternLayout layout =
      layout_pattern(draw_pattern_pieces(pattern, options, "test"), options);
  EXPECT_NEAR(full.width_pt, layout.width_mm * 72.0 / 25.4, 0.01);
  EXPECT_NEAR(full.height_pt, layout.height_mm * 72.0 / 25.4, 0.01);
  EXPECT_EQ(full.pages, 1);
  // The tiles cover exactly that box: page count from the measured sizes.
  const double full_w_mm = full.width_pt * 25.4 / 72.0;
  const double full_h_mm = full.height_pt * 25.4 / 72.0;
  const int cols = expected_tiles(full_w_mm, page_w_pt * 25.4 / 72.0, 12.0, 10.0);
  const int rows = expected_tiles(full_h_mm, page_h_pt * 25.4 / 72.0, 12.0, 10.0);
  EXPECT_GE(cols, 2);
  EXPECT_GE(rows, 2);
  EXPECT_EQ(tiles.pages, cols * rows);
}

TEST(PatternPdf, TiledA4PageSizeAndCount) { check_tiled(Paper::kA4, 595.276, 841.89, "pdf_a4"); }

TEST(PatternPdf, TiledLetterPageSizeAndCount) {
  check_tiled(Paper::kLetter, 612.0, 792.0, "pdf_letter");
}

TEST(PatternPdf, FullSizeSinglePageForPlotters) {
  test::require_program(kPdfInfo);
  const auto dir = test::scratch_dir("pdf_full");
  PatternExportOptions options;  // default 1.5 m layout width: one row
  const Pattern pattern = test::test_pattern();
  write_pattern_pdf_full_size(pattern, options, dir / "full.pdf");
  const PdfInfo info = pdf_info(dir / "full.pdf");
  const PatternLayout layout =
      layout_pattern(draw_pattern_pieces(pattern, options, "test"), options);
  EXPECT_EQ(info.pages, 1);
  EXPECT_NEAR(info.width_pt, layout.width_mm * 72.0 / 25.4, 0.01);
  EXPECT_NEAR(info.height_pt, layout.height_mm * 72.0 / 25.4, 0.01);
  // Test square + three pieces in one row: 10 + 100 + 10 + 320 + 10 + ... mm.
  EXPECT_GT(layout.width_mm, 100.0 + 320.0 + 320.0 + 260.0);
}

TEST(PatternPdf, TilesReassembleToTheFullSizePage) {
  test::require_program(kPdfToPpm);
  const auto dir = test::scratch_dir("pdf_mosaic");
  const PatternExportOptions options = tiled_options(Paper::kA4);
  const Pattern pattern = test::test_pattern();
  write_pattern_pdf_tiled(pattern, options, dir / "tiles.pdf");
  write_pattern_pdf_full_size(pattern, options, dir / "full.pdf");
  // 50.8 dpi = 2 px per mm.
  const double px_per_mm = 2.0;
  for (const char* name : {"tiles", "full"}) {
    const auto r = run_command(std::string(kPdfToPpm) + " -r 50.8 -gray " +
                               shell_quote(dir / (std::string(name) + ".pdf")) + " " +
                               shell_quote(dir / name));
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  std::vector<std::filesystem::path> tile_files;
  std::filesystem::path full_file;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string f = entry.path().filename().string();
    if (f.rfind("tiles-", 0) == 0) tile_files.push_back(entry.path());
    if (f.rfind("full-", 0) == 0) full_file = entry.path();
  }
  std::sort(tile_files.begin(), tile_files.end());
  const test::GrayImage full = test::read_pgm(full_file);
  const PatternLayout layout =
      layout_pattern(draw_pattern_pieces(pattern, options, "test"), options);
  const TileGrid grid = tile_grid(layout, options);
  ASSERT_EQ(tile_files.size(), static_cast<size_t>(grid.rows * grid.cols));
  // Paste each tile's content area at its place in the layout.
  test::GrayImage mosaic;
  mosaic.width = full.width;
  mosaic.height = full.height;
  mosaic.pixels.assign(full.pixels.size(), 255);
  const int margin = static_cast<int>(std::lround(grid.margin_mm * px_per_mm));
  const int content_w = static_cast<int>(std::lround(grid.content_width_mm * px_per_mm));
  const int content_h = static_cast<int>(std::lround(grid.content_height_mm * px_per_mm));
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const test::GrayImage tile =
          test::read_pgm(tile_files[static_cast<size_t>(r * grid.cols + c)]);
      const int x0 = static_cast<int>(std::lround(c * grid.step_x_mm() * px_per_mm));
      const int y0 = static_cast<int>(std::lround(r * grid.step_y_mm() * px_per_mm));
      for (int y = 1; y < content_h - 1; ++y) {
        for (int x = 1; x < content_w - 1; ++x) {
          const int mx = x0 + x;
          const int my = y0 + y;
          if (mx >= mosaic.width || my >= mosaic.height) continue;
          auto& dst = mosaic.pixels[static_cast<size_t>(my) * static_cast<size_t>(mosaic.width) +
                                    static_cast<size_t>(mx)];
          dst = std::min(dst, tile.at(margin + x, margin + y));
        }
      }
    }
  }
  // Every inked pixel of the full-size page is inked (±1 px) in the mosaic of tiles.
  size_t ink = 0;
  size_t matched = 0;
  for (int y = 1; y + 1 < full.height; ++y) {
    for (int x = 1; x + 1 < full.width; ++x) {
      if (full.at(x, y) > 160) continue;
      ++ink;
      bool found = false;
      for (int dy = -1; dy <= 1 && !found; ++dy) {
        for (int dx = -1; dx <= 1 && !found; ++dx) found = mosaic.at(x + dx, y + dy) < 220;
      }
      matched += found ? 1 : 0;
    }
  }
  ASSERT_GT(ink, 1000u);
  RecordProperty("ink_pixels", std::to_string(ink));
  RecordProperty("ink_matched", std::to_string(matched));
  EXPECT_GT(static_cast<double>(matched) / static_cast<double>(ink), 0.995)
      << matched << "/" << ink;
}

TEST(PatternPdf, FirstPageCarriesTheTestSquareAtTrueSize) {
  test::require_program(kPdfToPpm);
  const auto dir = test::scratch_dir("pdf_square");
  const PatternExportOptions options = tiled_options(Paper::kA4);
  const Pattern pattern = test::test_pattern();
  write_pattern_pdf_tiled(pattern, options, dir / "tiles.pdf");
  const auto r = run_command(std::string(kPdfToPpm) + " -r 96 -gray -f 1 -l 1 -singlefile " +
                             shell_quote(dir / "tiles.pdf") + " " + shell_quote(dir / "page1"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const test::GrayImage page = test::read_pgm(dir / "page1.pgm");
  const PatternLayout layout =
      layout_pattern(draw_pattern_pieces(pattern, options, "test"), options);
  const double px_per_mm = 96.0 / 25.4;
  const double margin = options.page_margin * 1000.0;
  const Box2& s = layout.test_square;
  const int window = static_cast<int>(3.0 * px_per_mm);
  const int row = static_cast<int>((margin + s.min.y() + 80.0) * px_per_mm);
  const int col = static_cast<int>((margin + s.min.x() + 80.0) * px_per_mm);
  auto px = [&](double mm) { return static_cast<int>((margin + mm) * px_per_mm); };
  const double left = test::ink_centre_x(page, row, px(s.min.x()) - window, px(s.min.x()) + window);
  const double right =
      test::ink_centre_x(page, row, px(s.max.x()) - window, px(s.max.x()) + window);
  const double top = test::ink_centre_y(page, col, px(s.min.y()) - window, px(s.min.y()) + window);
  const double bottom =
      test::ink_centre_y(page, col, px(s.max.y()) - window, px(s.max.y()) + window);
  RecordProperty("square_width_px", std::to_string(right - left));
  RecordProperty("square_height_px", std::to_string(bottom - top));
  EXPECT_NEAR(right - left, 100.0 * px_per_mm, 1.0);
  EXPECT_NEAR(bottom - top, 100.0 * px_per_mm, 1.0);
}

TEST(PatternPdf, InvalidPatternLeavesNoFile) {
  const auto dir = test::scratch_dir("pdf_invalid");
  Pattern pattern = test::test_pattern();
  pattern.pieces[0].boundary.push_back(500);
  EXPECT_THROW(write_pattern_pdf_tiled(pattern, {}, dir / "tiles.pdf"), InputError);
  EXPECT_THROW(write_pattern_pdf_full_size(pattern, {}, dir / "full.pdf"), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace tightfit::pattern_pdf_test
