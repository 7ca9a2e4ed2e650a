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

/// The most tetrahedra a body's volume is meshed into, counted as the least TetGen can
/// make: the volume divided by the largest tetrahedron allowed (TetGen makes about three
/// times as many). A full body at 1 cm edges needs about 75 000.
inline constexpr double kMaxVolumeTets = 5e5;

/// Throws InputError(source, …) when a volume of `volume` (m³) meshed with tetrahedra of
/// at most `max_tet_volume` (m³) needs more than kMaxVolumeTets of them.
inline void check_tet_budget(double volume, double max_tet_volume, const std::string& source) {
  if (!(max_tet_volume > 0.0)) return;
  const double n = volume / max_tet_volume;
  if (n <= kMaxVolumeTets) return;
  char text[320];
  std::snprintf(text, sizeof text,
                "its volume (%.3g m³) would be meshed into at least %.3g tetrahedra (none larger "
                "than %.3g m³), more than %.3g: choose a larger edge_length or "
                "interior_edge_length (lengths are in metres)",
                volume, n, max_tet_volume, kMaxVolumeTets);
  throw InputError(source, text);
}

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
