#include "tightfit/report/fabric_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "tightfit/common/xml_text.hpp"
#include "tightfit/physics/fabric_curve.hpp"

namespace tightfit {
namespace {

constexpr double kWidth = 720, kHeight = 440, kLeft = 64, kRight = 110, kTop = 40, kBottom = 48;

std::string number(double v, int digits = 3) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  return text;
}

const std::map<std::string, std::string> kColors = {
    {"wale", "#e08a1e"}, {"course", "#2a6fdb"}, {"bias", "#2e9e4f"}};

}  // namespace

std::string fabric_fit_svg(const FabricFit& fit, const std::string& title) {
  double x_max = 0.0, y_max = 0.0;
  for (const FittedDirection& d : fit.directions)
    for (const auto& [e, t] : d.samples) {
      x_max = std::max(x_max, e);
      y_max = std::max(y_max, t);
    }
  x_max = x_max > 0.0 ? x_max : 1.0;
  y_max = y_max > 0.0 ? 1.05 * y_max : 1.0;
  auto sx = [&](double e) {
    return kLeft + std::clamp(e / x_max, 0.0, 1.0) * (kWidth - kLeft - kRight);
  };
  auto sy = [&](double t) {
    return kHeight - kBottom - std::clamp(t / y_max, -0.05, 1.0) * (kHeight - kTop - kBottom);
  };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" viewBox=\"0 0 " << kWidth << " " << kHeight
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n"
      << "<text x=\"" << kLeft << "\" y=\"22\" font-size=\"14\" font-weight=\"bold\">"
      << xml_escape(title) << "</text>\n"
      << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << kWidth - kLeft - kRight
      << "\" height=\"" << kHeight - kTop - kBottom << "\" fill=\"#f7f8fa\" stroke=\"#d5dae0\"/>\n";
  for (int k = 0; k <= 4; ++k) {
    const double e = x_max * k / 4, t = y_max * k / 4;
    svg << "<text x=\"" << sx(e) << "\" y=\"" << kHeight - kBottom + 16
        << "\" text-anchor=\"middle\">" << number(100 * e) << " %</text>\n"
        << "<text x=\"" << kLeft - 6 << "\" y=\"" << sy(t) + 4 << "\" text-anchor=\"end\">"
        << number(t) << "</text>\n";
  }
  svg << "<text x=\"" << (kLeft + kWidth - kRight) / 2 << "\" y=\"" << kHeight - 10
      << "\" text-anchor=\"middle\">strain</text>\n"
      << "<text x=\"14\" y=\"" << (kTop + kHeight - kBottom) / 2 << "\" transform=\"rotate(-90 14 "
      << (kTop + kHeight - kBottom) / 2
      << ")\" text-anchor=\"middle\">tension (N/m of strip width)</text>\n";
  int row = 0;
  for (const FittedDirection& d : fit.directions) {
    const std::string& color = kColors.at(d.direction);
    svg << "<polyline class=\"samples " << d.direction << "\" fill=\"none\" stroke=\"" << color
        << "\" stroke-opacity=\"0.35\" stroke-width=\"1\" points=\"";
    for (const auto& [e, t] : d.samples) svg << sx(e) << "," << sy(t) << " ";
    svg << "\"/>\n";
    auto curve = [&](const std::vector<double>& strain, const std::vector<double>& tension,
                     const char* kind, const char* dash) {
      if (strain.size() < 2) return;
      const FabricCurve c(strain, tension);
      svg << "<polyline class=\"fit " << kind << " " << d.direction << "\" fill=\"none\" stroke=\""
          << color << "\" stroke-width=\"2\"" << dash << " points=\"";
      for (int k = 0; k <= 96; ++k) {
        const double e = strain.back() * k / 96;
        svg << sx(e) << "," << sy(c.tension(e)) << " ";
      }
      svg << "\"/>\n";
      for (std::size_t k = 0; k < strain.size(); ++k)
        svg << "<circle cx=\"" << sx(strain[k]) << "\" cy=\"" << sy(tension[k])
            << "\" r=\"3\" fill=\"#fff\" stroke=\"" << color << "\" stroke-width=\"1.5\"/>\n";
    };
    curve(d.loading_strain, d.loading_tension, "loading", "");
    curve(d.unloading_strain, d.unloading_tension, "unloading", " stroke-dasharray=\"6 4\"");
    svg << "<text x=\"" << kWidth - kRight + 8 << "\" y=\"" << kTop + 14 + 34 * row << "\" fill=\""
        << color << "\">" << d.direction << "</text>\n"
        << "<text x=\"" << kWidth - kRight + 8 << "\" y=\"" << kTop + 28 + 34 * row
        << "\" font-size=\"10\" fill=\"#5b6570\">cycle " << d.cycle << " of " << d.cycles
        << "</text>\n";
    ++row;
  }
  svg << "<text x=\"" << kWidth - kRight + 8 << "\" y=\"" << kTop + 20 + 34 * row
      << "\" font-size=\"10\" fill=\"#5b6570\">thin: data</text>\n"
      << "<text x=\"" << kWidth - kRight + 8 << "\" y=\"" << kTop + 34 + 34 * row
      << "\" font-size=\"10\" fill=\"#5b6570\">solid: loading</text>\n"
      << "<text x=\"" << kWidth - kRight + 8 << "\" y=\"" << kTop + 48 + 34 * row
      << "\" font-size=\"10\" fill=\"#5b6570\">dashed: unloading</text>\n"
      << "</svg>\n";
  return svg.str();
}

}  // namespace tightfit
