#pragma once
/// A bound on the size of the meshes tightfit builds, checked from the input before
/// meshing: an edge length or a size given in millimetres where metres are expected
/// would otherwise ask for billions of triangles and end in an out-of-memory crash
/// after minutes.
#include <cmath>
#include <cstdio>
#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit {

/// The most triangles one surface (a body, a pattern) is meshed into. A full body at
/// 5 mm edges has about 170 000.
inline constexpr double kMaxSurfaceTriangles = 2e6;

/// Triangles of a surface of `area` (m²) meshed with equilateral triangles of edge `h` (m).
inline double expected_triangles(double area, double h) {
  return area / (std::sqrt(3.0) / 4.0 * h * h);
}

/// Why meshing `area` (m², e.g. of the "body surface") at edge length `h` (m) is refused
/// (more than kMaxSurfaceTriangles triangles), or "" when it is not.
inline std::string mesh_budget_problem(double area, double h, const std::string& what) {
  const double n = expected_triangles(area, h);
  if (n <= kMaxSurfaceTriangles) return "";
  char text[256];
  std::snprintf(text, sizeof text,
                "an edge length of %.3g m would mesh the %s (%.3g m²) into about %.3g triangles, "
                "more than %.3g: "
                "lengths are in metres (5 mm is 0.005)",
                h, what.c_str(), area, n, kMaxSurfaceTriangles);
  return text;
}

/// Throws InputError(source, mesh_budget_problem(…)) when there is one.
inline void check_mesh_budget(double area, double h, const std::string& what,
                              const std::string& source) {
  if (const std::string problem = mesh_budget_problem(area, h, what); !problem.empty())
    throw InputError(source, problem);
}

}  // namespace tightfit
