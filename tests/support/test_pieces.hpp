#pragma once
/// Pattern pieces built in code, shared by the design and objectives tests.
#include <random>

#include "tightfit/garment/pattern.hpp"

namespace tightfit::test {

/// An nx × ny grid piece over [0,w]×[0,h], interior vertices jittered by up to `jitter`
/// of the spacing (< 0.25 keeps every triangle counter-clockwise on a square grid),
/// random diagonals; boundary counter-clockwise, corners marked.
inline PatternPiece grid_piece(int nx, int ny, double w, double h, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  PatternPiece piece;
  piece.name = "grid";
  auto id = [&](int i, int j) { return j * nx + i; };
  piece.rest.resize(nx * ny, 2);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const bool inner = i > 0 && j > 0 && i < nx - 1 && j < ny - 1;
      piece.rest.row(id(i, j)) << w * (i + (inner ? u(rng) : 0.0)) / (nx - 1),
          h * (j + (inner ? u(rng) : 0.0)) / (ny - 1);
    }
  piece.triangles.resize(2 * (nx - 1) * (ny - 1), 3);
  int t = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (jitter > 0.0 && rng() % 2) {
        piece.triangles.row(t++) << a, b, d;
        piece.triangles.row(t++) << b, c, d;
      } else {
        piece.triangles.row(t++) << a, b, c;
        piece.triangles.row(t++) << a, c, d;
      }
    }
  for (int i = 0; i < nx - 1; ++i) piece.boundary.push_back(id(i, 0));
  for (int j = 0; j < ny - 1; ++j) piece.boundary.push_back(id(nx - 1, j));
  for (int i = nx - 1; i > 0; --i) piece.boundary.push_back(id(i, ny - 1));
  for (int j = ny - 1; j > 0; --j) piece.boundary.push_back(id(0, j));
  piece.corners = {id(0, 0), id(nx - 1, 0), id(nx - 1, ny - 1), id(0, ny - 1)};
  return piece;
}

}  // namespace tightfit::test
