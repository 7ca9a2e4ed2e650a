#include "tightfit/patterns/svg.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/patterns/drawing.hpp"
#include "tightfit/patterns/layout.hpp"
#include "tightfit/patterns/text.hpp"

namespace tightfit {
namespace {

std::string point(const Vec2& q) { return fixed(q.x(), 4) + "," + fixed(q.y(), 4); }

std::string path_data(const PatternLayout& layout, size_t piece, const Polygon2& polygon) {
  std::string d;
  for (size_t i = 0; i < polygon.size(); ++i) {
    d += (i == 0 ? "M" : " L") + point(layout.to_layout(piece, polygon[i]));
  }
  return d + " Z";
}

std::string line(const Vec2& a, const Vec2& b) {
  return "<line x1=\"" + fixed(a.x(), 4) + "\" y1=\"" + fixed(a.y(), 4) + "\" x2=\"" +
         fixed(b.x(), 4) + "\" y2=\"" + fixed(b.y(), 4) + "\"/>";
}

std::string text(const Vec2& at, double size_mm, const std::string& content,
                 const std::string& css_class) {
  return "<text class=\"" + css_class + "\" x=\"" + fixed(at.x(), 3) + "\" y=\"" +
         fixed(at.y(), 3) + "\" font-size=\"" + fixed(size_mm, 2) + "\">" + xml_escape(content) +
         "</text>";
}

/// A placed text (piece plane) in layout coordinates, rotated along its direction.
std::string placed_text(const PatternLayout& layout, size_t piece, const PlacedText& t,
                        const std::string& css_class) {
  const Vec2 at = layout.to_layout(piece, t.at);
  std::string out = "<text class=\"" + css_class + "\" x=\"" + fixed(at.x(), 3) + "\" y=\"" +
                    fixed(at.y(), 3) + "\" font-size=\"" + fixed(t.height, 2) + "\"";
  if (t.bold) out += " font-weight=\"bold\"";
  // Layout y points down: the piece direction (x, y) is (x, −y) there.
  const double angle = std::atan2(-t.direction.y(), t.direction.x()) * 180.0 / std::numbers::pi;
  if (std::abs(angle) > 1e-9) {
    out += " transform=\"rotate(" + fixed(angle, 3) + " " + fixed(at.x(), 3) + " " +
           fixed(at.y(), 3) + ")\"";
  }
  return out + ">" + xml_escape(t.text) + "</text>";
}

/// An open arrow head at `tip`, pointing away from `from`.
std::string arrow_head(const Vec2& tip, const Vec2& from) {
  const Vec2 back = (from - tip).normalized() * 6.0;
  const Vec2 side(-back.y() * 0.4, back.x() * 0.4);
  return "<path d=\"M" + point(tip + back + side) + " L" + point(tip) + " L" +
         point(tip + back - side) + "\"/>";
}

void write_piece(std::ostream& out, const PieceDrawing& piece, const PatternLayout& layout,
                 size_t p, const std::string& id, const PatternExportOptions& options) {
  out << "<g id=\"" << id << "\">\n<title>" << xml_escape(piece.name) << "</title>\n";
  out << "<path class=\"cut\" d=\"" << path_data(layout, p, piece.cut_line) << "\"/>\n";
  for (const Polygon2& hole : piece.holes)
    out << "<path class=\"cut opening\" d=\"" << path_data(layout, p, hole) << "\"/>\n";
  out << "<path class=\"sew\" d=\"" << path_data(layout, p, piece.trued_sew_line) << "\"/>\n";
  out << "<g class=\"notches\">\n";
  for (const Notch& n : piece.notches) {
    for (const auto& tick : n.ticks)
      out << line(layout.to_layout(p, tick[0]), layout.to_layout(p, tick[1])) << "\n";
  }
  out << "</g>\n<g class=\"grain\">\n";
  const Vec2 a = layout.to_layout(p, piece.grain_start);
  const Vec2 b = layout.to_layout(p, piece.grain_end);
  out << line(a, b) << "\n";
  if ((b - a).norm() > 0.0) out << arrow_head(b, a) << "\n" << arrow_head(a, b) << "\n";
  out << "</g>\n";
  if (!piece.seam_texts.empty()) {
    out << "<g class=\"seams\">\n";
    for (const PlacedText& t : piece.seam_texts) out << placed_text(layout, p, t, "seam") << "\n";
    out << "</g>\n";
  }
  if (options.piece_labels) {
    out << "<g class=\"piece-label\">\n";
    for (const PlacedText& t : piece.label)
      out << placed_text(layout, p, t, t.bold ? "label" : "note") << "\n";
    out << "</g>\n";
  }
  out << "</g>\n";
}

}  // namespace

void write_pattern_svg(const Pattern& pattern, const PatternExportOptions& options,
                       const std::filesystem::path& path) {
  const std::vector<PieceDrawing> pieces = draw_pattern_pieces(pattern, options, path.string());
  const PatternLayout layout = layout_pattern(pieces, options);
  write_file_atomically(path, [&](std::ostream& out) {
    const std::string w = fixed(layout.width_mm, 3);
    const std::string h = fixed(layout.height_mm, 3);
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << w
        << "mm\" height=\"" << h << "mm\" viewBox=\"0 0 " << w << " " << h << "\">\n"
        << "<title>tightfit pattern</title>\n"
        << "<desc>Scale 1:1, user units are millimetres. Cut on the solid line, sew on the "
           "dashed line; match the notches of each seam (single notches: front seams, double: "
           "back seams); grain line (arrows at both ends: no nap) parallel to the selvage.</desc>\n"
        << "<style>\n"
        << "path, line { fill: none; stroke: #000; stroke-linecap: round; "
           "stroke-linejoin: round; }\n"
        << ".cut { stroke-width: 0.4; }\n"
        << ".sew { stroke-width: 0.25; stroke-dasharray: 3 1.5; stroke: #1a4fd0; }\n"
        << ".notches line { stroke-width: 0.4; stroke: #c00000; }\n"
        << ".grain line, .grain path { stroke-width: 0.35; stroke: #007a2e; }\n"
        << "text { font-family: sans-serif; fill: #000; }\n"
        << "text.seam { fill: #1a4fd0; }\n"
        << "#test-square rect { fill: none; stroke: #000; stroke-width: 0.3; }\n"
        << "</style>\n";
    if (layout.has_test_square) {
      const Box2& s = layout.test_square;
      out << "<g id=\"test-square\">\n<rect x=\"" << fixed(s.min.x(), 4) << "\" y=\""
          << fixed(s.min.y(), 4) << "\" width=\"" << fixed(kTestSquareMm, 4) << "\" height=\""
          << fixed(kTestSquareMm, 4) << "\"/>\n"
          << text(s.min + Vec2(8.0, 45.0), 7.0, "10 cm", "label") << "\n"
          << text(s.min + Vec2(8.0, 55.0), 4.0, "test square: measure 100 mm", "note") << "\n"
          << "</g>\n";
    }
    std::set<std::string> ids{"test-square"};
    for (size_t p = 0; p < pieces.size(); ++p) {
      const std::string id = unique_identifier("piece-" + pieces[p].name, ids);
      write_piece(out, pieces[p], layout, p, id, options);
    }
    out << "</svg>\n";
  });
}

}  // namespace tightfit
