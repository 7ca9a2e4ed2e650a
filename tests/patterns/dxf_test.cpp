#include "tightfit/patterns/dxf.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>

#include "patterns/support/pattern_fixtures.hpp"
#include "patterns/support/pattern_tools.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/layout.hpp"

namespace tightfit::pattern_dxf_test {

using test::run_command;
using test::shell_quote;

const char* const kPython = "/usr/bin/python3";
const char* const kLibreCad = "/usr/bin/librecad";
const char* const kPdfToPpm = "/usr/bin/pdftoppm";

/// The test pattern with a non-ASCII piece name and options exercising every layer.
Pattern dxf_pattern() {
  Pattern pattern = test::test_pattern();
  pattern.pieces[2].name = "\xC3\x84rmel";  // "Ärmel"
  return pattern;
}

PatternExportOptions dxf_options() {
  PatternExportOptions options;
  options.seam_allowances["side_left"] = 0.015;
  options.annotations["front"] = "Front, cut on fold: no";
  options.quantities["back"] = 2;
  // Double notches, "top" marks and style text go through the audit and LibreCAD too.
  options.seam_notch_styles["side_left"] = NotchStyle::kDouble;
  options.seam_last_end_up["side_right"] = true;
  options.label.style = "Test style";
  options.label.date = "2001-02-03";
  return options;
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(PatternDxf, IsSevenBitAsciiR12WithUnitsStated) {
  const auto dir = test::scratch_dir("dxf_ascii");
  const auto file = dir / "pattern.dxf";
  write_pattern_dxf(dxf_pattern(), dxf_options(), file);
  const std::string text = read_bytes(file);
  for (char c : text) ASSERT_LT(static_cast<unsigned char>(c), 128u);
  EXPECT_NE(text.find("$ACADVER\n1\nAC1009\n"), std::string::npos);
  EXPECT_NE(text.find("$INSUNITS\n70\n4\n"), std::string::npos);
  EXPECT_NE(text.find("$MEASUREMENT\n70\n1\n"), std::string::npos);
  EXPECT_NE(text.find("999\nunits: millimetres"), std::string::npos);
  EXPECT_NE(text.find("Piece Name: \\U+00C4rmel"), std::string::npos);
  EXPECT_EQ(text.substr(text.size() - 6), "0\nEOF\n");
}

TEST(PatternDxf, EzdxfAuditFindsNoErrors) {
  test::require_program(kPython);
  const auto dir = test::scratch_dir("dxf_audit");
  const auto file = dir / "pattern.dxf";
  write_pattern_dxf(dxf_pattern(), dxf_options(), file);
  const auto audit = run_command(std::string(kPython) + " -m ezdxf audit " + shell_quote(file));
  EXPECT_EQ(audit.exit_code, 0) << audit.output;
  // ezdxf 0.18 "fixes" the owner handle of SEQENDs of POLYLINEs inside R12 blocks even
  // in files it wrote itself; those are fixes, not errors.
  const bool clean = audit.output.find("No errors found") != std::string::npos ||
                     audit.output.find("Found 0 errors") != std::string::npos;
  EXPECT_TRUE(clean) << audit.output;
  EXPECT_EQ(audit.output.find("Error"), std::string::npos) << audit.output;
}

TEST(PatternDxf, EzdxfReadsBackPiecesOutlinesAndLayers) {
  test::require_program(kPython);
  const auto dir = test::scratch_dir("dxf_read");
  const auto file = dir / "pattern.dxf";
  const Pattern pattern = dxf_pattern();
  const PatternExportOptions options = dxf_options();
  write_pattern_dxf(pattern, options, file);
  const auto read = run_command(
      std::string(kPython) + " " +
      shell_quote(std::string(TIGHTFIT_SOURCE_DIR) + "/tests/patterns/pattern_dxf_check.py") + " " +
      shell_quote(file));
  ASSERT_EQ(read.exit_code, 0) << read.output;
  const nlohmann::json found = nlohmann::json::parse(read.output);
  EXPECT_EQ(found["dxfversion"], "AC1009");
  EXPECT_EQ(found["insunits"], 4);
  EXPECT_EQ(found["measurement"], 1);

  const auto pieces = draw_pattern_pieces(pattern, options, "test");
  const PatternLayout layout = layout_pattern(pieces, options);
  const std::vector<std::string> names = {"front", "back", "__rmel"};
  ASSERT_EQ(found["blocks"].size(), pieces.size());
  ASSERT_EQ(found["inserts"].size(), pieces.size());
  for (size_t p = 0; p < pieces.size(); ++p) {
    SCOPED_TRACE(names[p]);
    ASSERT_TRUE(found["blocks"].contains(names[p]));
    const auto& block = found["blocks"][names[p]];
    ASSERT_EQ(block["cut"].size(), 1u);
    ASSERT_EQ(block["sew"].size(), 1u);
    EXPECT_TRUE(block["cut"][0]["closed"].get<bool>());
    EXPECT_TRUE(block["sew"][0]["closed"].get<bool>());
    const double cut = test::perimeter(pieces[p].cut_line);
    // The sew line drawn is the trued one (patterns/truing.hpp).
    const double sew = test::perimeter(pieces[p].trued_sew_line);
    EXPECT_NEAR(block["cut"][0]["length"].get<double>(), cut, 1e-9 * cut);
    EXPECT_NEAR(block["sew"][0]["length"].get<double>(), sew, 1e-9 * sew);
    EXPECT_EQ(block["cut"][0]["vertices"].get<size_t>(), pieces[p].cut_line.size());
    EXPECT_EQ(block["sew"][0]["vertices"].get<size_t>(), pieces[p].trued_sew_line.size());
    size_t ticks = 0;
    for (const Notch& n : pieces[p].notches) ticks += n.ticks.size();
    EXPECT_EQ(block["notches"].size(), ticks);
    // The grain line, then two strokes of each of its two arrow heads.
    ASSERT_EQ(block["grain"].size(), 5u);
    EXPECT_NEAR(block["grain"][0][0].get<double>(), pieces[p].grain_start.x(), 1e-6);
    EXPECT_NEAR(block["grain"][0][3].get<double>(), pieces[p].grain_end.y(), 1e-6);
    EXPECT_TRUE(block["other_layers"].empty()) << block["other_layers"];
    const auto& texts = block["texts"];
    ASSERT_EQ(texts.size(), 3u);
    EXPECT_EQ(texts[0].get<std::string>().rfind("Piece Name: ", 0), 0u);
    EXPECT_EQ(texts[1], "Quantity: " + std::to_string(pieces[p].quantity));
    EXPECT_EQ(texts[2], "Annotation: " + pieces[p].annotation);
    const auto& insert = found["inserts"][p];
    EXPECT_EQ(insert[0], names[p]);
    EXPECT_NEAR(insert[1].get<double>(), layout.offsets[p].x(), 1e-6);
    EXPECT_NEAR(insert[2].get<double>(), layout.height_mm - layout.offsets[p].y(), 1e-6);
  }
  EXPECT_EQ(found["blocks"]["front"]["texts"][0], "Piece Name: front");
  EXPECT_EQ(found["blocks"]["back"]["texts"][1], "Quantity: 2");
  EXPECT_EQ(found["blocks"]["front"]["texts"][2], "Annotation: Front, cut on fold: no");
}

TEST(PatternDxf, LibreCadRendersIt) {
  test::require_program(kLibreCad);
  test::require_program(kPdfToPpm);
  const auto dir = test::scratch_dir("dxf_librecad");
  const auto file = dir / "pattern.dxf";
  write_pattern_dxf(dxf_pattern(), dxf_options(), file);
  const auto runtime = dir / "xdg";
  std::filesystem::create_directories(runtime);
  std::filesystem::permissions(runtime, std::filesystem::perms::owner_all);
  // LibreCAD 2.2 needs a Qt platform; the offscreen one needs no display.
  const auto render =
      run_command("cd " + shell_quote(dir) + " && QT_QPA_PLATFORM=offscreen XDG_RUNTIME_DIR=" +
                  shell_quote(runtime) + " " + kLibreCad + " dxf2pdf -a -m pattern.dxf");
  ASSERT_EQ(render.exit_code, 0) << render.output;
  ASSERT_TRUE(std::filesystem::exists(dir / "pattern.pdf")) << render.output;
  const auto raster =
      run_command(std::string(kPdfToPpm) + " -r 40 -gray -singlefile " +
                  shell_quote(dir / "pattern.pdf") + " " + shell_quote(dir / "page"));
  ASSERT_EQ(raster.exit_code, 0) << raster.output;
  const test::GrayImage image = test::read_pgm(dir / "page.pgm");
  ASSERT_GT(image.width, 100);
  size_t dark = 0;
  for (unsigned char v : image.pixels) dark += v < 128 ? 1 : 0;
  const double fraction = static_cast<double>(dark) / static_cast<double>(image.pixels.size());
  EXPECT_GT(fraction, 0.002) << "LibreCAD rendered a blank page";
  EXPECT_LT(fraction, 0.5);
}

TEST(PatternDxf, InvalidPatternLeavesNoFile) {
  const auto dir = test::scratch_dir("dxf_invalid");
  Pattern pattern = test::test_pattern();
  pattern.seams[0].a.vertices.pop_back();
  EXPECT_THROW(write_pattern_dxf(pattern, {}, dir / "pattern.dxf"), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace tightfit::pattern_dxf_test
