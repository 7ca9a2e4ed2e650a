// The pattern exports as the garment trade expects them: double notches on back seams,
// seam and boundary names on the pieces, "top" marks, double-headed grain lines, piece
// labels inside the sew line, AAMA turn/curve points and style text.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "objectives/objective_test_garments.hpp"
#include "patterns/support/pattern_fixtures.hpp"
#include "patterns/support/pattern_tools.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/dxf.hpp"
#include "tightfit/patterns/layout.hpp"
#include "tightfit/patterns/pdf.hpp"
#include "tightfit/patterns/scene_options.hpp"
#include "tightfit/patterns/svg.hpp"
#include "tightfit/patterns/truing.hpp"

namespace tightfit {
namespace trade_test {

using test::run_command;
using test::shell_quote;

/// A sleeve of 9 × 6 grid vertices wrapped around the z axis (radius 5 cm, 30 cm long),
/// its one seam ("axial seam") at +x, sides running bottom to top.
test::GarmentState small_sleeve() {
  return test::sleeve(9, 6, 0.05, 2.0 * std::numbers::pi * 0.05, 0.30, 0.0, 1);
}

Points3 positions_of(const test::GarmentState& s) {
  Points3 x(s.garment.num_garment_vertices(), 3);
  for (int i = 0; i < s.garment.num_garment_vertices(); ++i)
    x.row(i) = s.x.segment<3>(3 * i).transpose();
  return x;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// One SVG <text>: class, position, size, rotation (deg) and content, in layout mm.
struct SvgText {
  std::string css_class;
  Vec2 at;
  double size = 0.0;
  double angle = 0.0;
  std::string content;
};

/// The <text> elements of the group of piece `id`.
std::vector<SvgText> svg_texts(const std::string& svg, const std::string& id) {
  const std::string open = "<g id=\"" + id + "\">";
  const size_t begin = svg.find(open);
  EXPECT_NE(begin, std::string::npos) << id;
  if (begin == std::string::npos) return {};
  const size_t end = svg.find("\n</g>\n<g id=", begin + open.size());
  const std::string group =
      svg.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  static const std::regex text(
      R"re(<text class="([a-z]+)" x="([-0-9.]+)" y="([-0-9.]+)" font-size="([0-9.]+)"(?: font-weight="bold")?(?: transform="rotate\(([-0-9.]+) [-0-9.]+ [-0-9.]+\)")?>([^<]*)</text>)re");
  std::vector<SvgText> out;
  for (auto it = std::sregex_iterator(group.begin(), group.end(), text);
       it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    SvgText t;
    t.css_class = m[1];
    t.at = Vec2(std::stod(m[2]), std::stod(m[3]));
    t.size = std::stod(m[4]);
    t.angle = m[5].matched ? std::stod(m[5]) : 0.0;
    t.content = m[6];
    out.push_back(t);
  }
  return out;
}

/// An SVG text back in the piece's plane (layout y points down).
PlacedText to_piece(const SvgText& t, const PatternLayout& layout, size_t piece) {
  const double a = t.angle * std::numbers::pi / 180.0;
  const Vec2 offset = layout.offsets[piece];
  PlacedText p;
  p.text = t.content;
  p.at = Vec2(t.at.x() - offset.x(), offset.y() - t.at.y());
  p.direction = Vec2(std::cos(a), -std::sin(a));
  p.height = t.size;
  return p;
}

size_t count_of(const std::vector<SvgText>& texts, const std::string& content) {
  return static_cast<size_t>(std::count_if(texts.begin(), texts.end(),
                                           [&](const SvgText& t) { return t.content == content; }));
}

TEST(PatternTrade, BackSeamsAndUpperEndsFromThe3DState) {
  const test::GarmentState s = small_sleeve();
  const Points3 x = positions_of(s);
  // The seam lies at +x of the sleeve's axis: behind it when the body faces −x.
  EXPECT_EQ(classify_seam_notches(s.garment, x, -Vec3::UnitX()).at("axial seam"),
            NotchStyle::kDouble);
  EXPECT_EQ(classify_seam_notches(s.garment, x, Vec3::UnitX()).at("axial seam"),
            NotchStyle::kSingle);
  EXPECT_EQ(classify_seam_notches(s.garment, x, Vec3::Zero()).at("axial seam"),
            NotchStyle::kSingle);
  EXPECT_TRUE(seam_upper_ends(s.garment, x, Vec3::UnitZ()).at("axial seam"));
  EXPECT_FALSE(seam_upper_ends(s.garment, x, -Vec3::UnitZ()).at("axial seam"));
  EXPECT_TRUE(seam_upper_ends(s.garment, x, Vec3::UnitY()).empty());  // level: no mark
  BodySpec mesh_body;
  mesh_body.source = BodySource::kMesh;
  EXPECT_EQ(body_front_direction(mesh_body), Vec3::UnitZ());
  EXPECT_EQ(body_front_direction(BodySpec{}), Vec3::Zero());  // a cylinder has no front
}

TEST(PatternTrade, DoubleNotchesAreTwoParallelTicksAlikeOnBothSides) {
  const test::GarmentState s = small_sleeve();
  PatternExportOptions options;
  options.seam_notch_styles = classify_seam_notches(s.garment, positions_of(s), -Vec3::UnitX());
  const auto pieces = draw_pattern_pieces(s.garment.pattern, options, "test");
  ASSERT_EQ(pieces.size(), 1u);
  size_t per_side[2] = {0, 0};
  for (const Notch& n : pieces[0].notches) {
    SCOPED_TRACE(n.index);
    ++per_side[n.side];
    EXPECT_EQ(n.style, NotchStyle::kDouble);
    ASSERT_EQ(n.ticks.size(), 2u);
    const Vec2 t0 = n.ticks[0][1] - n.ticks[0][0];
    const Vec2 t1 = n.ticks[1][1] - n.ticks[1][0];
    EXPECT_NEAR(t0.norm(), 4.0, 1e-9);
    EXPECT_NEAR(t1.norm(), 4.0, 1e-9);
    EXPECT_NEAR(cross2(t0, t1), 0.0, 1e-9);  // parallel
    EXPECT_NEAR((n.ticks[1][0] - n.ticks[0][0]).norm(), 3.0, 1e-9);
    EXPECT_NEAR((n.ticks[1][0] - n.ticks[0][0]).dot(t0), 0.0, 1e-9);  // side by side
    const bool end = n.index == 0 || n.index + 1 == static_cast<int>(pieces[0].notches.size() / 2);
    if (end) {
      // At the seam's ends the pair starts at the notch and runs into the seam.
      EXPECT_TRUE(n.ticks[0][0] == n.sew || n.ticks[1][0] == n.sew);
    } else {
      EXPECT_TRUE((0.5 * (n.ticks[0][0] + n.ticks[1][0])).isApprox(n.sew, 1e-12));
    }
    EXPECT_LT(test::polygon_distance(n.ticks[1][0], pieces[0].trued_sew_line), 1e-6);
    // The ticks start on the trued sew line and point outward.
    EXPECT_LT(test::polygon_distance(n.ticks[0][0], pieces[0].trued_sew_line), 1e-6);
    EXPECT_FALSE(test::inside_polygon(n.ticks[0][1], pieces[0].trued_sew_line));
  }
  EXPECT_GT(per_side[0], 2u);
  EXPECT_EQ(per_side[0], per_side[1]);
  // Without the classification: single notches.
  const auto plain = draw_pattern_pieces(s.garment.pattern, {}, "test");
  for (const Notch& n : plain[0].notches) EXPECT_EQ(n.ticks.size(), 1u);
}

TEST(PatternTrade, SvgSeamNamesOnBothPiecesBoundaryNamesAndTopMarks) {
  const auto dir = test::scratch_dir("trade_svg_seams");
  const Pattern pattern = test::test_pattern();
  PatternExportOptions options;
  options.seam_last_end_up["side_right"] = true;
  options.seam_last_end_up["sleeve_hem"] = false;
  write_pattern_svg(pattern, options, dir / "pattern.svg");
  const std::string svg = read_text(dir / "pattern.svg");
  const auto pieces = draw_pattern_pieces(pattern, options, "test");
  const PatternLayout layout = layout_pattern(pieces, options);
  const std::vector<std::string> ids = {"piece-front", "piece-back", "piece-sleeve"};
  std::vector<std::vector<SvgText>> texts;
  for (const std::string& id : ids) texts.push_back(svg_texts(svg, id));
  // side_right and side_left join front and back, sleeve_hem sleeve and back.
  for (size_t p : {0u, 1u}) {
    SCOPED_TRACE(ids[p]);
    EXPECT_EQ(count_of(texts[p], "side_right"), 1u);
    EXPECT_EQ(count_of(texts[p], "side_left"), 1u);
  }
  EXPECT_EQ(count_of(texts[1], "sleeve_hem"), 1u);
  EXPECT_EQ(count_of(texts[2], "sleeve_hem"), 1u);
  EXPECT_EQ(count_of(texts[0], "waist"), 1u);  // the pinned boundary
  // "top": side_right on front and back, sleeve_hem on sleeve and back.
  EXPECT_EQ(count_of(texts[0], "top"), 1u);
  EXPECT_EQ(count_of(texts[1], "top"), 2u);
  EXPECT_EQ(count_of(texts[2], "top"), 1u);
  for (size_t p = 0; p < pieces.size(); ++p) {
    for (const SvgText& t : texts[p]) {
      SCOPED_TRACE(ids[p] + ": " + t.content);
      // Every text box inside the sew line.
      const PlacedText placed = to_piece(t, layout, p);
      EXPECT_TRUE(text_inside(placed, pieces[p].trued_sew_line));
      EXPECT_TRUE(test::inside_polygon(placed.at, pieces[p].trued_sew_line));
      EXPECT_GE(t.size, kMinTextHeightMm - 1e-9);
    }
  }
  // The front's right side is vertical: its seam name runs along it (rotated ±90°).
  for (const SvgText& t : texts[0]) {
    if (t.content == "side_right") {
      EXPECT_NEAR(std::abs(t.angle), 90.0, 1e-6);
    }
  }
  // "top" of side_right sits at the upper end of the side (y = 400 mm on the front).
  for (const SvgText& t : texts[0]) {
    if (t.content != "top") continue;
    const PlacedText placed = to_piece(t, layout, 0);
    EXPECT_GT(placed.at.y(), 300.0);
    EXPECT_GT(placed.at.x(), 280.0);
  }
  // The top mark of sleeve_hem on the sleeve (first end up: x = 0 end of its bottom).
  for (const SvgText& t : texts[2]) {
    if (t.content != "top") continue;
    EXPECT_LT(to_piece(t, layout, 2).at.x(), 120.0);
  }
}

TEST(PatternTrade, SvgNotchesAreNotchDepthLong) {
  const auto dir = test::scratch_dir("trade_svg_notches");
  const Pattern pattern = test::test_pattern();
  PatternExportOptions options;
  options.notch_depth = 0.005;
  options.seam_allowances["side_left"] = 0.003;  // shallower than the notch: clamped
  options.seam_notch_styles["sleeve_hem"] = NotchStyle::kDouble;
  write_pattern_svg(pattern, options, dir / "pattern.svg");
  const std::string svg = read_text(dir / "pattern.svg");
  const auto pieces = draw_pattern_pieces(pattern, options, "test");
  static const std::regex line(
      R"re(<line x1="([-0-9.]+)" y1="([-0-9.]+)" x2="([-0-9.]+)" y2="([-0-9.]+)"/>)re");
  size_t from = 0;
  size_t five = 0;
  size_t three = 0;
  for (size_t p = 0; p < pieces.size(); ++p) {
    const size_t begin = svg.find("<g class=\"notches\">", from);
    ASSERT_NE(begin, std::string::npos);
    const size_t end = svg.find("</g>", begin);
    from = end;
    const std::string group = svg.substr(begin, end - begin);
    size_t lines = 0;
    for (auto it = std::sregex_iterator(group.begin(), group.end(), line);
         it != std::sregex_iterator(); ++it) {
      const Vec2 a(std::stod((*it)[1]), std::stod((*it)[2]));
      const Vec2 b(std::stod((*it)[3]), std::stod((*it)[4]));
      const double length = (b - a).norm();
      ++lines;
      if (std::abs(length - 5.0) < 1e-3) ++five;
      if (std::abs(length - 3.0) < 1e-3) ++three;
    }
    size_t ticks = 0;
    for (const Notch& n : pieces[p].notches) ticks += n.ticks.size();
    EXPECT_EQ(lines, ticks);
  }
  // side_left: 5 notches on each of its 2 sides, 3 mm deep (its allowance); every
  // other tick 5 mm: side_right 2 × 5, sleeve_hem 2 × 3 notches × 2 ticks.
  EXPECT_EQ(three, 10u);
  EXPECT_EQ(five, 10u + 12u);
}

TEST(PatternTrade, PdfCarriesSeamNamesTopMarksAndTheLabel) {
  test::require_program("/usr/bin/pdftotext");
  const auto dir = test::scratch_dir("trade_pdf");
  PatternExportOptions options;
  options.seam_last_end_up["side_right"] = true;
  options.label.style = "Racer";
  options.label.date = "2001-02-03";
  write_pattern_pdf_full_size(test::test_pattern(), options, dir / "pattern.pdf");
  const auto text = run_command("/usr/bin/pdftotext " + shell_quote(dir / "pattern.pdf") + " -");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  for (const char* word : {"side_right", "side_left", "sleeve_hem", "waist", "top", "Racer",
                           "2001-02-03", "cut 1", "front", "sleeve"})
    EXPECT_NE(text.output.find(word), std::string::npos) << word << " in " << text.output;
}

TEST(PatternTrade, SvgGrainLineHasArrowHeadsAtBothEnds) {
  const auto dir = test::scratch_dir("trade_svg_grain");
  const Pattern pattern = test::test_pattern();
  write_pattern_svg(pattern, {}, dir / "pattern.svg");
  const std::string svg = read_text(dir / "pattern.svg");
  const auto pieces = draw_pattern_pieces(pattern, {}, "test");
  const PatternLayout layout = layout_pattern(pieces, {});
  static const std::regex head(
      R"re(<path d="M[-0-9.]+,[-0-9.]+ L([-0-9.]+),([-0-9.]+) L[-0-9.]+,[-0-9.]+"/>)re");
  size_t from = 0;
  for (size_t p = 0; p < pieces.size(); ++p) {
    const size_t begin = svg.find("<g class=\"grain\">", from);
    ASSERT_NE(begin, std::string::npos);
    const size_t end = svg.find("</g>", begin);
    from = end;
    const std::string group = svg.substr(begin, end - begin);
    std::vector<Vec2> tips;
    for (auto it = std::sregex_iterator(group.begin(), group.end(), head);
         it != std::sregex_iterator(); ++it)
      tips.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
    ASSERT_EQ(tips.size(), 2u) << group;
    EXPECT_LT((tips[0] - layout.to_layout(p, pieces[p].grain_end)).norm(), 1e-3);
    EXPECT_LT((tips[1] - layout.to_layout(p, pieces[p].grain_start)).norm(), 1e-3);
  }
}

TEST(PatternTrade, PieceLabelShrinksToFitInsideTheSewLine) {
  // A narrow piece (the sleeve, 6 cm wide) with a long label: style, fabric, size, date
  // and two note lines; every line's box lies inside the sew line.
  const test::GarmentState s = small_sleeve();
  Pattern pattern = s.garment.pattern;
  for (int v = 0; v < pattern.pieces[0].rest.rows(); ++v) pattern.pieces[0].rest(v, 0) *= 0.2;
  PatternExportOptions options;
  options.label.style = "Racer tights";
  options.label.size = "M";
  options.label.date = "2001-02-03";
  options.label.youngs_modulus = 5.4e6;
  options.label.thickness = 5e-4;
  options.label.stretch_min = 1.05;
  options.label.stretch_max = 1.3;
  options.piece_notes["grid"] = {"negative ease -12 % at the calf",
                                 "negative ease -8 % at the knee"};
  const auto pieces = draw_pattern_pieces(pattern, options, "test");
  const PieceDrawing& d = pieces[0];
  std::vector<std::string> lines;
  for (const PlacedText& t : d.label) lines.push_back(t.text);
  const std::vector<std::string> expected = {"Racer tights",
                                             "grid",
                                             "cut 1",
                                             "fabric E 5.4 MPa, 0.5 mm, stretch 1.05 to 1.3",
                                             "size M",
                                             "2001-02-03",
                                             d.annotation,
                                             "negative ease -12 % at the calf",
                                             "negative ease -8 % at the knee"};
  EXPECT_EQ(lines, expected);
  double smallest = 1e9;
  for (const PlacedText& t : d.label) {
    SCOPED_TRACE(t.text);
    EXPECT_TRUE(text_inside(t, d.trued_sew_line));
    smallest = std::min(smallest, t.height);
  }
  EXPECT_LT(smallest, 3.0);  // shrunk to fit the 60 mm width
  EXPECT_GE(smallest, kMinTextHeightMm - 1e-9);
  // The SVG carries the same lines inside the piece.
  const auto dir = test::scratch_dir("trade_label");
  write_pattern_svg(pattern, options, dir / "pattern.svg");
  const std::string svg = read_text(dir / "pattern.svg");
  const PatternLayout layout = layout_pattern(pieces, options);
  const std::vector<SvgText> texts = svg_texts(svg, "piece-grid");
  for (const std::string& line : expected) EXPECT_EQ(count_of(texts, line), 1u) << line;
  for (const SvgText& t : texts)
    EXPECT_TRUE(text_inside(to_piece(t, layout, 0), d.trued_sew_line)) << t.content;
}

TEST(PatternTrade, DxfLayersTwoThreeFourAndStyleTextReadByEzdxf) {
  test::require_program("/usr/bin/python3");
  const test::GarmentState s = small_sleeve();
  PatternExportOptions options;
  options.seam_notch_styles = classify_seam_notches(s.garment, positions_of(s), -Vec3::UnitX());
  options.seam_last_end_up = seam_upper_ends(s.garment, positions_of(s), Vec3::UnitZ());
  options.label.style = "Sleeve";
  options.label.size = "M";
  options.label.date = "2001-02-03";
  const auto dir = test::scratch_dir("trade_dxf");
  const auto file = dir / "pattern.dxf";
  write_pattern_dxf(s.garment.pattern, options, file);
  const auto audit = run_command("/usr/bin/python3 -m ezdxf audit " + shell_quote(file));
  EXPECT_EQ(audit.exit_code, 0) << audit.output;
  EXPECT_EQ(audit.output.find("Error"), std::string::npos) << audit.output;
  std::string script = TIGHTFIT_SOURCE_DIR;
  script += "/tests/patterns/pattern_dxf_check.py";
  const auto read =
      run_command("/usr/bin/python3 " + shell_quote(script) + " " + shell_quote(file));
  ASSERT_EQ(read.exit_code, 0) << read.output;
  const nlohmann::json found = nlohmann::json::parse(read.output);
  const auto pieces = draw_pattern_pieces(s.garment.pattern, options, "test");
  const PieceDrawing& d = pieces[0];
  const auto& block = found["blocks"]["grid"];
  // Layer 4: both ticks of every (double) notch.
  EXPECT_EQ(block["notches"].size(), 2 * d.notches.size());
  for (const auto& n : block["notches"]) {
    const Vec2 a(n[0].get<double>(), n[1].get<double>());
    const Vec2 b(n[2].get<double>(), n[3].get<double>());
    EXPECT_NEAR((b - a).norm(), 4.0, 1e-6);  // the default notch depth
  }
  // Layers 2 and 3: one POINT per cut-line vertex; the four mitred corners are turn points.
  EXPECT_EQ(block["turn_points"].size() + block["curve_points"].size(), d.cut_line.size());
  EXPECT_GE(block["turn_points"].size(), 4u);
  for (const char* layer : {"turn_points", "curve_points"}) {
    for (const auto& q : block[layer]) {
      const Vec2 point(q[0].get<double>(), q[1].get<double>());
      double best = 1e9;
      for (const Vec2& c : d.cut_line) best = std::min(best, (c - point).norm());
      EXPECT_LT(best, 1e-6) << layer;
    }
  }
  // Texts inside the sew line: the system texts (layer 1) and the annotations (15).
  for (const char* layer : {"system_texts", "annotations"}) {
    for (const auto& t : block[layer]) {
      PlacedText placed;
      placed.text = t[0].get<std::string>();
      placed.at = Vec2(t[1].get<double>(), t[2].get<double>());
      placed.height = t[3].get<double>();
      const double a = t[4].get<double>() * std::numbers::pi / 180.0;
      placed.direction = Vec2(std::cos(a), std::sin(a));
      EXPECT_TRUE(text_inside(placed, d.trued_sew_line)) << layer << ": " << placed.text;
    }
  }
  std::vector<std::string> annotations;
  for (const auto& t : block["annotations"]) annotations.push_back(t[0].get<std::string>());
  EXPECT_EQ(std::count(annotations.begin(), annotations.end(), "axial seam"), 2);
  EXPECT_EQ(std::count(annotations.begin(), annotations.end(), "top"), 2);
  // Style text outside the blocks.
  const auto& style = found["style_texts"];
  for (const char* text : {"Style Name: Sleeve", "Creation Date: 2001-02-03", "Author: tightfit",
                           "Sample Size: M", "Units: METRIC"})
    EXPECT_NE(std::find(style.begin(), style.end(), text), style.end()) << text << " in " << style;
}

}  // namespace trade_test
}  // namespace tightfit

namespace tightfit {
namespace trade_test {

SceneSpec cylinder_scene(const nlohmann::json& patterns) {
  nlohmann::json j = nlohmann::json::parse(R"({
      "body": {"generator": "cylinder", "radius": 0.05, "length": 0.3, "edge_length": 0.01},
      "garment": {"sleeve": {"radius": 0.05}},
      "fabric": {"youngs_modulus": 6e6, "thickness": 4e-4, "relaxation": 0.1},
      "optimize": {"objectives": {"stretch": {"min": 1.05, "max": 1.2}}}})");
  if (!patterns.is_null()) j["patterns"] = patterns;
  return parse_scene(j, "/some/where/racer.json", ".");
}

TEST(PatternTrade, RunOptionsFromTheSceneAndTheGarmentOnTheBody) {
  const test::GarmentState s = small_sleeve();
  const Points3 x = positions_of(s);
  PatternExportOptions o =
      scene_pattern_export_options(cylinder_scene(nullptr), s.garment, x, "2001-02-03");
  // A cylinder has no front: single notches; up is its axis (+z): the seam's last end.
  EXPECT_EQ(o.seam_notch_styles.at("axial seam"), NotchStyle::kSingle);
  EXPECT_TRUE(o.seam_last_end_up.at("axial seam"));
  EXPECT_EQ(o.label.style, "racer");
  EXPECT_EQ(o.label.size, "cylinder");
  EXPECT_EQ(o.label.date, "2001-02-03");
  EXPECT_NEAR(o.label.youngs_modulus, 6e6, 1e-3);  // before relaxation
  EXPECT_DOUBLE_EQ(o.label.thickness, 4e-4);
  EXPECT_DOUBLE_EQ(o.label.stretch_min, 1.05);
  EXPECT_DOUBLE_EQ(o.label.stretch_max, 1.2);
  EXPECT_DOUBLE_EQ(o.notch_depth, 0.004);
  // The scene's section: an explicit rule wins, style and size given.
  o = scene_pattern_export_options(cylinder_scene({{"notches", {{"axial seam", "double"}}},
                                                   {"style", "Sleeve"},
                                                   {"size", "S"},
                                                   {"notch_depth", 0.005}}),
                                   s.garment, x, "2001-02-03");
  EXPECT_EQ(o.seam_notch_styles.at("axial seam"), NotchStyle::kDouble);
  EXPECT_EQ(o.label.style, "Sleeve");
  EXPECT_EQ(o.label.size, "S");
  EXPECT_DOUBLE_EQ(o.notch_depth, 0.005);
  // A seam the garment does not have: the scene file and JSON path are named.
  try {
    scene_pattern_export_options(cylinder_scene({{"seam_allowances", {{"hem", 0.02}}}}), s.garment,
                                 x, "");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("racer.json: /patterns/seam_allowances/hem"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace trade_test
}  // namespace tightfit

namespace tightfit {
namespace trade_test {

TEST(PatternTrade, PieceLabelStaysClearOfAnOpening) {
  // A 200 mm square with an 80 mm square opening around its centroid: the label goes
  // beside the opening, inside the piece (SVG and DXF alike use place_text_block).
  PatternPiece piece;
  piece.name = "mask";
  piece.rest.resize(8, 2);
  piece.rest << 0.0, 0.0, 0.2, 0.0, 0.2, 0.2, 0.0, 0.2,  // outer, counter-clockwise
      0.06, 0.06, 0.06, 0.14, 0.14, 0.14, 0.14, 0.06;    // opening, clockwise
  piece.triangles.resize(1, 3);
  piece.triangles << 0, 1, 4;
  piece.boundary = {0, 1, 2, 3};
  piece.holes = {{4, 5, 6, 7}};
  piece.corners = {0, 1, 2, 3};
  Pattern pattern;
  pattern.pieces.push_back(piece);
  PatternExportOptions options;
  options.label.style = "Mask";
  options.label.date = "2001-02-03";
  const auto pieces = draw_pattern_pieces(pattern, options, "test");
  const PieceDrawing& d = pieces[0];
  ASSERT_FALSE(d.label.empty());
  for (const PlacedText& t : d.label) {
    SCOPED_TRACE(t.text);
    EXPECT_TRUE(text_inside(t, d.trued_sew_line));
    EXPECT_TRUE(text_clear_of(t, d.holes[0]));
  }
  // The centroid lies in the opening: the label could not stay there.
  EXPECT_TRUE(test::inside_polygon(d.centroid, d.holes[0]));
}

}  // namespace trade_test
}  // namespace tightfit
