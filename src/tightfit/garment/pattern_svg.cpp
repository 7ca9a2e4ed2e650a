#include "tightfit/garment/pattern_svg.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <sstream>
#include <vector>

#include "tightfit/common/atomic_file.hpp"

namespace tightfit {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3f", x);
  return buf;
}

const char* kSeamColors[] = {"#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b",
                             "#e377c2", "#17becf", "#bcbd22", "#1f77b4", "#7f7f7f"};

}  // namespace

std::string pattern_svg(const Pattern& pattern, const SvgOptions& options) {
  // Place the pieces (metres) in rows.
  std::vector<Vec2> shift(pattern.pieces.size(), Vec2::Zero());
  double x = options.gap, y = options.gap, row_height = 0.0, width = 0.0;
  for (size_t k = 0; k < pattern.pieces.size(); ++k) {
    const Points2& r = pattern.pieces[k].rest;
    if (r.rows() == 0) continue;
    const Vec2 lo = r.colwise().minCoeff().transpose(), hi = r.colwise().maxCoeff().transpose();
    const Vec2 size = hi - lo;
    if (x > options.gap && x + size.x() > options.row_width) {
      x = options.gap;
      y += row_height + options.gap;
      row_height = 0.0;
    }
    shift[k] = Vec2(x, y) - lo;
    x += size.x() + options.gap;
    row_height = std::max(row_height, size.y());
    width = std::max(width, x);
  }
  const double height = y + row_height + options.gap;
  const double mm = 1000.0;
  // SVG coordinates (mm, y down) of a piece point, as "x,y" or as two attributes.
  auto svg_point = [&](const Vec2& p, size_t k) { return Vec2((p + shift[k]).x() * mm, (height - (p + shift[k]).y()) * mm); };
  auto px = [&](const Vec2& p, size_t k) {
    const Vec2 q = svg_point(p, k);
    return num(q.x()) + "," + num(q.y());
  };
  auto attrs = [&](const Vec2& p, size_t k, const char* xname, const char* yname) {
    const Vec2 q = svg_point(p, k);
    return std::string(" ") + xname + "=\"" + num(q.x()) + "\" " + yname + "=\"" + num(q.y()) + "\"";
  };

  std::ostringstream s;
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width * mm) << "mm\" height=\""
    << num(height * mm) << "mm\" viewBox=\"0 0 " << num(width * mm) << " " << num(height * mm) << "\">\n";
  for (size_t k = 0; k < pattern.pieces.size(); ++k) {
    const PatternPiece& piece = pattern.pieces[k];
    s << "<g id=\"piece-" << escape(piece.name) << "\">\n";
    if (options.draw_triangles && piece.triangles.rows() > 0) {
      s << "<path fill=\"none\" stroke=\"#bbbbbb\" stroke-width=\"0.2\" d=\"";
      for (Eigen::Index f = 0; f < piece.triangles.rows(); ++f)
        s << "M" << px(piece.rest.row(piece.triangles(f, 0)), k) << "L" << px(piece.rest.row(piece.triangles(f, 1)), k)
          << "L" << px(piece.rest.row(piece.triangles(f, 2)), k) << "Z";
      s << "\"/>\n";
    }
    if (!piece.boundary.empty()) {
      s << "<polygon fill=\"none\" stroke=\"black\" stroke-width=\"0.6\" points=\"";
      for (int v : piece.boundary) s << px(piece.rest.row(v), k) << " ";
      s << "\"/>\n";
    }
    for (size_t j = 0; j < pattern.seams.size(); ++j)
      for (const SeamSide* side : {&pattern.seams[j].a, &pattern.seams[j].b}) {
        if (side->piece != static_cast<int>(k) || side->vertices.empty()) continue;
        s << "<polyline fill=\"none\" stroke=\"" << kSeamColors[j % 10] << "\" stroke-width=\"1.5\" points=\"";
        for (int v : side->vertices) s << px(piece.rest.row(v), k) << " ";
        s << "\"/>\n";
        const Vec2 mid = piece.rest.row(side->vertices[side->vertices.size() / 2]);
        s << "<text" << attrs(mid, k, "x", "y") << " font-size=\"6\" fill=\"" << kSeamColors[j % 10]
          << "\">" << escape(pattern.seams[j].name) << "</text>\n";
      }
    for (const PinnedBoundary& pin : pattern.pinned) {
      if (pin.piece != static_cast<int>(k)) continue;
      s << "<polyline fill=\"none\" stroke=\"#1f3fff\" stroke-width=\"1.2\" stroke-dasharray=\"4,2\" points=\"";
      for (int v : pin.vertices) s << px(piece.rest.row(v), k) << " ";
      s << "\"/>\n";
    }
    for (int v : piece.corners) s << "<circle" << attrs(piece.rest.row(v), k, "cx", "cy") << " r=\"1.5\" fill=\"black\"/>\n";
    if (piece.rest.rows() > 0) {
      const Vec2 c = piece.rest.colwise().mean().transpose();
      const double len = 0.25 * (piece.rest.col(1).maxCoeff() - piece.rest.col(1).minCoeff());
      s << "<line" << attrs(c - len * piece.grain, k, "x1", "y1") << attrs(c + len * piece.grain, k, "x2", "y2")
        << " stroke=\"#555555\" stroke-width=\"0.8\"/>\n";
      s << "<text" << attrs(c, k, "x", "y") << " font-size=\"10\" text-anchor=\"middle\">" << escape(piece.name)
        << "</text>\n";
    }
    s << "</g>\n";
  }
  s << "</svg>\n";
  return s.str();
}

void write_pattern_svg(const std::filesystem::path& path, const Pattern& pattern, const SvgOptions& options) {
  write_text_atomically(path, pattern_svg(pattern, options));
}

}  // namespace tightfit
