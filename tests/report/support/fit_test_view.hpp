#pragma once
/// A small fit built by hand for the export tests: a sphere body (radius 0.1 m, y up),
/// a band garment around its equator made of two pattern pieces (front and back
/// halves, welded at two seams) and synthetic fields with known values.
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "tightfit/report/fit_view.hpp"

namespace tightfit::test {

inline constexpr double kSphereRadius = 0.1;

/// Latitude-longitude sphere with outward (counter-clockwise) faces.
inline TriMesh uv_sphere(double radius, int rings, int segments) {
  TriMesh m;
  const int n = 2 + (rings - 1) * segments;
  m.vertices.resize(n, 3);
  m.vertices.row(0) << 0, radius, 0;
  m.vertices.row(n - 1) << 0, -radius, 0;
  for (int r = 1; r < rings; ++r) {
    const double phi = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double theta = 2 * std::numbers::pi * s / segments;
      m.vertices.row(1 + (r - 1) * segments + s) << radius * std::sin(phi) * std::sin(theta),
          radius * std::cos(phi), radius * std::sin(phi) * std::cos(theta);
    }
  }
  std::vector<Eigen::Vector3i> faces;
  auto ring = [&](int r, int s) {
    return 1 + (r - 1) * segments + ((s % segments) + segments) % segments;
  };
  for (int s = 0; s < segments; ++s) faces.emplace_back(0, ring(1, s), ring(1, s + 1));
  for (int r = 1; r < rings - 1; ++r) {
    for (int s = 0; s < segments; ++s) {
      faces.emplace_back(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      faces.emplace_back(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  }
  for (int s = 0; s < segments; ++s)
    faces.emplace_back(n - 1, ring(rings - 1, s + 1), ring(rings - 1, s));
  m.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    m.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
  return m;
}

/// The synthetic pressure (Pa) at angle theta around the y axis: high on the "front"
/// piece (theta in 0..pi), negative (lift-off) in a sector of the "back" piece.
inline double test_pressure(double theta) { return 400.0 + 2400.0 * std::sin(theta); }

/// The synthetic max stretch at height y (m): 1.05 at the band's edges, 1.35 mid-band.
inline double test_stretch_max(double y, double half_height) {
  return 1.05 + 0.3 * (1.0 - std::abs(y) / half_height);
}

/// Builds the test fit. `cols` quads around each half, `rows` quads in height.
inline FitView band_on_sphere(int cols = 24, int rows = 6) {
  FitView view;
  view.body = uv_sphere(kSphereRadius, 24, 48);
  const double half_height = 0.04;
  const int around = 2 * cols;  // garment vertex columns (closed ring)
  view.garment.vertices.resize(around * (rows + 1), 3);
  for (int j = 0; j <= rows; ++j) {
    const double y = -half_height + 2 * half_height * j / rows;
    const double r = std::sqrt(kSphereRadius * kSphereRadius - y * y) * 1.002;
    for (int i = 0; i < around; ++i) {
      const double theta = 2 * std::numbers::pi * i / around;
      view.garment.vertices.row(j * around + i) << r * std::sin(theta), y, r * std::cos(theta);
    }
  }
  view.garment.faces.resize(2 * 2 * cols * rows, 3);
  int face = 0;
  const char* names[2] = {"front", "back"};
  for (int k = 0; k < 2; ++k) {
    PatternPiece piece;
    piece.name = names[k];
    piece.rest.resize((cols + 1) * (rows + 1), 2);
    const double width = std::numbers::pi * kSphereRadius / 1.2;  // 20 % smaller than the body
    for (int j = 0; j <= rows; ++j) {
      for (int i = 0; i <= cols; ++i) {
        piece.rest.row(j * (cols + 1) + i) << width * i / cols, 2 * half_height / 1.1 * j / rows;
      }
    }
    piece.triangles.resize(2 * cols * rows, 3);
    int t = 0;
    for (int j = 0; j < rows; ++j) {
      for (int i = 0; i < cols; ++i) {
        const int a = j * (cols + 1) + i, b = a + 1, c = a + cols + 2, d = a + cols + 1;
        piece.triangles.row(t++) << a, b, c;
        piece.triangles.row(t++) << a, c, d;
        // The same quad on the garment ring (piece k covers columns k*cols .. (k+1)*cols).
        const int gi = k * cols + i;
        const int ga = j * around + gi, gb = j * around + (gi + 1) % around;
        const int gc = (j + 1) * around + (gi + 1) % around, gd = (j + 1) * around + gi;
        view.garment.faces.row(face++) << ga, gb, gc;
        view.garment.faces.row(face++) << ga, gc, gd;
      }
    }
    for (int i = 0; i <= cols; ++i) piece.boundary.push_back(i);
    for (int j = 1; j <= rows; ++j) piece.boundary.push_back(j * (cols + 1) + cols);
    for (int i = cols - 1; i >= 0; --i) piece.boundary.push_back(rows * (cols + 1) + i);
    for (int j = rows - 1; j >= 1; --j) piece.boundary.push_back(j * (cols + 1));
    piece.corners = {0, cols, (rows + 1) * (cols + 1) - 1, rows * (cols + 1)};
    piece.grain = Vec2::UnitY();
    view.pattern.pieces.push_back(std::move(piece));
  }

  const int m = view.garment.num_faces();
  FaceField stretch_max{"stretch_max", "", MatX(m, 1)};
  FaceField stretch_min{"stretch_min", "", MatX(m, 1)};
  FaceField stretch_dir{"stretch_dir", "", MatX(m, 3)};
  FaceField regime{"regime", "", MatX(m, 1)};
  FaceField pressure{"pressure_pa", "Pa", MatX(m, 1)};
  FaceField force{"normal_force_n", "N", MatX(m, 1)};
  for (int f = 0; f < m; ++f) {
    const Vec3 a = view.garment.vertices.row(view.garment.faces(f, 0));
    const Vec3 b = view.garment.vertices.row(view.garment.faces(f, 1));
    const Vec3 c = view.garment.vertices.row(view.garment.faces(f, 2));
    const Vec3 centroid = (a + b + c) / 3.0;
    const double theta = std::atan2(centroid.x(), centroid.z());
    const double area = 0.5 * (b - a).cross(c - a).norm();
    stretch_max.values(f, 0) = test_stretch_max(centroid.y(), half_height);
    stretch_min.values(f, 0) = 0.97 + 0.06 * std::sin(theta);
    stretch_dir.values.row(f) << std::cos(theta), 0.0, -std::sin(theta);
    regime.values(f, 0) =
        stretch_min.values(f, 0) > 1.0 ? 2.0 : (std::cos(theta) > -0.5 ? 1.0 : 0.0);
    pressure.values(f, 0) = test_pressure(theta);
    force.values(f, 0) = pressure.values(f, 0) * area;
  }
  view.garment_fields = {stretch_max, stretch_min, stretch_dir,
                         regime,      pressure,    pressure_mmhg_field(pressure),
                         force};
  view.parameters = {
      {"body", {{"generator", "sphere"}, {"radius_m", kSphereRadius}}},
      {"fabric", {{"thickness_m", 1e-4}, {"young_modulus_pa", 5.4e6}, {"poisson", 0.33}}}};
  for (int it = 0; it < 12; ++it) {
    const double stretch = 2.0 * std::exp(-0.5 * it), spacing = it == 0 ? 0.0 : 0.01;
    view.history.push_back({{"iteration", it},
                            {"objective", stretch + spacing},
                            {"terms", {{"stretch", stretch}, {"boundary spacing", spacing}}}});
  }
  return view;
}

}  // namespace tightfit::test
