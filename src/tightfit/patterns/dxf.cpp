#include "tightfit/patterns/dxf.hpp"

#include <cmath>
#include <numbers>
#include <ostream>
#include <set>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/layout.hpp"
#include "tightfit/patterns/text.hpp"
#include "tightfit/patterns/truing.hpp"

namespace tightfit {
namespace {

constexpr int kDecimals = 9;
/// Style text: height and line pitch (mm); it is written below the layout (y < 0).
constexpr double kStyleTextMm = 4.0;
constexpr double kStyleTextPitchMm = 6.0;
constexpr double kStyleTextBlockMm = 6.0 * kStyleTextPitchMm + 4.0;
/// Boundary vertices turning more than this (rad) are turn points, the others curve points.
constexpr double kTurnPointAngle = 0.5235987755982988;  // 30°

/// Writes DXF group-code/value pairs.
class DxfWriter {
 public:
  explicit DxfWriter(std::ostream& out) : out_(out) {}
  void pair(int code, const std::string& value) { out_ << code << "\n" << value << "\n"; }
  void pair(int code, int value) { pair(code, std::to_string(value)); }
  void number(int code, double value) { pair(code, fixed(value, kDecimals)); }
  void point(int code, const Vec2& q) {
    number(code, q.x());
    number(code + 10, q.y());
    number(code + 20, 0.0);
  }
  void text(const std::string& layer, const Vec2& at, double height, const std::string& content,
            double angle_deg = 0.0) {
    pair(0, "TEXT");
    pair(8, layer);
    point(10, at);
    number(40, height);
    pair(1, ascii_escape(content).substr(0, 250));
    if (angle_deg != 0.0) number(50, angle_deg);
    pair(7, "STANDARD");
  }
  void text(const std::string& layer, const PlacedText& t) {
    text(layer, t.at, t.height, t.text,
         std::atan2(t.direction.y(), t.direction.x()) * 180.0 / std::numbers::pi);
  }
  void point_entity(const std::string& layer, const Vec2& q) {
    pair(0, "POINT");
    pair(8, layer);
    point(10, q);
  }
  void line(const std::string& layer, const Vec2& a, const Vec2& b) {
    pair(0, "LINE");
    pair(8, layer);
    point(10, a);
    point(11, b);
  }
  void closed_polyline(const std::string& layer, const Polygon2& polygon) {
    pair(0, "POLYLINE");
    pair(8, layer);
    pair(66, 1);
    point(10, Vec2::Zero());
    pair(70, 1);
    for (const Vec2& q : polygon) {
      pair(0, "VERTEX");
      pair(8, layer);
      point(10, q);
    }
    pair(0, "SEQEND");
    pair(8, layer);
  }

 private:
  std::ostream& out_;
};

void write_header(DxfWriter& dxf, const PatternLayout& layout) {
  dxf.pair(999, "tightfit pattern, AAMA/ASTM D6673 layout, ASCII DXF R12");
  dxf.pair(999, "units: millimetres (1 drawing unit = 1 mm), scale 1:1");
  dxf.pair(0, "SECTION");
  dxf.pair(2, "HEADER");
  dxf.pair(9, "$ACADVER");
  dxf.pair(1, "AC1009");
  dxf.pair(9, "$INSBASE");
  dxf.point(10, Vec2::Zero());
  dxf.pair(9, "$EXTMIN");
  dxf.point(10, Vec2(0.0, -kStyleTextBlockMm));
  dxf.pair(9, "$EXTMAX");
  dxf.point(10, Vec2(layout.width_mm, layout.height_mm));
  dxf.pair(9, "$INSUNITS");
  dxf.pair(70, 4);
  dxf.pair(9, "$MEASUREMENT");
  dxf.pair(70, 1);
  dxf.pair(9, "$LUNITS");
  dxf.pair(70, 2);
  dxf.pair(0, "ENDSEC");
}

void write_tables(DxfWriter& dxf) {
  dxf.pair(0, "SECTION");
  dxf.pair(2, "TABLES");
  dxf.pair(0, "TABLE");
  dxf.pair(2, "LTYPE");
  dxf.pair(70, 2);
  dxf.pair(0, "LTYPE");
  dxf.pair(2, "CONTINUOUS");
  dxf.pair(70, 0);
  dxf.pair(3, "Solid line");
  dxf.pair(72, 65);
  dxf.pair(73, 0);
  dxf.number(40, 0.0);
  dxf.pair(0, "LTYPE");
  dxf.pair(2, "DASHED");
  dxf.pair(70, 0);
  dxf.pair(3, "Dashed __ __ __");
  dxf.pair(72, 65);
  dxf.pair(73, 2);
  dxf.number(40, 4.5);
  dxf.number(49, 3.0);
  dxf.number(49, -1.5);
  dxf.pair(0, "ENDTAB");
  struct Layer {
    const char* name;
    int colour;
    const char* linetype;
  };
  const Layer layers[] = {{"0", 7, "CONTINUOUS"}, {"1", 7, "CONTINUOUS"}, {"2", 2, "CONTINUOUS"},
                          {"3", 4, "CONTINUOUS"}, {"4", 1, "CONTINUOUS"}, {"7", 3, "CONTINUOUS"},
                          {"14", 5, "DASHED"},    {"15", 6, "CONTINUOUS"}};
  dxf.pair(0, "TABLE");
  dxf.pair(2, "LAYER");
  dxf.pair(70, static_cast<int>(std::size(layers)));
  for (const Layer& layer : layers) {
    dxf.pair(0, "LAYER");
    dxf.pair(2, layer.name);
    dxf.pair(70, 0);
    dxf.pair(62, layer.colour);
    dxf.pair(6, layer.linetype);
  }
  dxf.pair(0, "ENDTAB");
  dxf.pair(0, "TABLE");
  dxf.pair(2, "STYLE");
  dxf.pair(70, 1);
  dxf.pair(0, "STYLE");
  dxf.pair(2, "STANDARD");
  dxf.pair(70, 0);
  dxf.number(40, 0.0);
  dxf.number(41, 1.0);
  dxf.number(50, 0.0);
  dxf.pair(71, 0);
  dxf.number(42, 2.5);
  dxf.pair(3, "txt");
  dxf.pair(4, "");
  dxf.pair(0, "ENDTAB");
  dxf.pair(0, "ENDSEC");
}

/// The piece's text: AAMA system text on layer 1 ("Piece Name:", "Quantity:",
/// "Annotation:", "Size:") and the other label lines on layer 15, as one block inside
/// the sew line.
void write_piece_text(DxfWriter& dxf, const PieceDrawing& piece,
                      const PatternExportOptions& options) {
  std::vector<TextLine> lines = {{"Piece Name: " + piece.name, 5.0, false},
                                 {"Quantity: " + std::to_string(piece.quantity), 4.0, false},
                                 {"Annotation: " + piece.annotation, 3.0, false}};
  if (!options.label.size.empty()) lines.push_back({"Size: " + options.label.size, 3.0, false});
  const size_t system = lines.size();
  // The label's own lines except the name, quantity and annotation said above.
  for (const TextLine& line : piece.label_lines) {
    if (line.text == piece.name || line.text == piece.annotation ||
        line.text == "cut " + std::to_string(piece.quantity) ||
        line.text == "size " + options.label.size)
      continue;
    lines.push_back({line.text, 3.0, false});
  }
  const std::vector<PlacedText> placed =
      place_text_block(piece.trued_sew_line, lines, piece.centroid, piece.holes);
  for (size_t k = 0; k < placed.size(); ++k) dxf.text(k < system ? "1" : "15", placed[k]);
}

void write_block(DxfWriter& dxf, const PieceDrawing& piece, const std::string& name,
                 const PatternExportOptions& options) {
  dxf.pair(0, "BLOCK");
  dxf.pair(8, "0");
  dxf.pair(2, name);
  dxf.pair(70, 0);
  dxf.point(10, Vec2::Zero());
  dxf.pair(3, name);
  dxf.closed_polyline("1", piece.cut_line);
  for (const Polygon2& hole : piece.holes) dxf.closed_polyline("1", hole);
  for (size_t k = 0; k < piece.cut_line.size(); ++k) {
    dxf.point_entity(turning_angle(piece.cut_line, k) > kTurnPointAngle ? "2" : "3",
                     piece.cut_line[k]);
  }
  dxf.closed_polyline("14", piece.trued_sew_line);
  for (const Notch& n : piece.notches)
    for (const auto& tick : n.ticks) dxf.line("4", tick[0], tick[1]);
  dxf.line("7", piece.grain_start, piece.grain_end);
  // Arrow heads at both ends (no nap), after the grain line itself.
  const Vec2 g = piece.grain_end - piece.grain_start;
  if (g.norm() > 0.0) {
    for (const auto& [tip, from] : {std::pair{piece.grain_end, piece.grain_start},
                                    std::pair{piece.grain_start, piece.grain_end}}) {
      const Vec2 back = (from - tip).normalized() * 6.0;
      const Vec2 side(-back.y() * 0.4, back.x() * 0.4);
      dxf.line("7", tip, tip + back + side);
      dxf.line("7", tip, tip + back - side);
    }
  }
  write_piece_text(dxf, piece, options);
  for (const PlacedText& t : piece.seam_texts) dxf.text("15", t);
  dxf.pair(0, "ENDBLK");
  dxf.pair(8, "0");
}

/// AAMA style system text, in ENTITIES below the layout.
void write_style_text(DxfWriter& dxf, const PatternExportOptions& options) {
  const PatternLabelInfo& info = options.label;
  std::vector<std::string> lines = {
      "Style Name: " + (info.style.empty() ? std::string("tightfit pattern") : info.style)};
  if (!info.date.empty()) lines.push_back("Creation Date: " + info.date);
  lines.push_back("Author: tightfit");
  if (!info.size.empty()) lines.push_back("Sample Size: " + info.size);
  lines.push_back("Units: METRIC");
  for (size_t k = 0; k < lines.size(); ++k) {
    dxf.text("1",
             Vec2(options.layout_gap * 1000.0, -kStyleTextPitchMm * static_cast<double>(k + 1)),
             kStyleTextMm, lines[k]);
  }
}

}  // namespace

void write_pattern_dxf(const Pattern& pattern, const PatternExportOptions& options,
                       const std::filesystem::path& path) {
  const std::vector<PieceDrawing> pieces = draw_pattern_pieces(pattern, options, path.string());
  const PatternLayout layout = layout_pattern(pieces, options);
  std::set<std::string> taken;
  std::vector<std::string> names;
  for (const PieceDrawing& piece : pieces) {
    names.push_back(unique_identifier(piece.name, taken, false));
  }
  write_file_atomically(path, [&](std::ostream& out) {
    DxfWriter dxf(out);
    write_header(dxf, layout);
    write_tables(dxf);
    dxf.pair(0, "SECTION");
    dxf.pair(2, "BLOCKS");
    for (size_t p = 0; p < pieces.size(); ++p) write_block(dxf, pieces[p], names[p], options);
    dxf.pair(0, "ENDSEC");
    dxf.pair(0, "SECTION");
    dxf.pair(2, "ENTITIES");
    write_style_text(dxf, options);
    for (size_t p = 0; p < pieces.size(); ++p) {
      dxf.pair(0, "INSERT");
      dxf.pair(8, "0");
      dxf.pair(2, names[p]);
      // Layout y points down; the DXF plane's y points up.
      dxf.point(10, Vec2(layout.offsets[p].x(), layout.height_mm - layout.offsets[p].y()));
    }
    dxf.pair(0, "ENDSEC");
    dxf.pair(0, "EOF");
  });
}

}  // namespace tightfit
