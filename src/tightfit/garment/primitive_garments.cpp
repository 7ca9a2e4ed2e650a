#include "tightfit/garment/primitive_garments.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <tuple>

#include <Eigen/Geometry>

#include "tightfit/common/error.hpp"
#include "tightfit/subdiv/limit_projector.hpp"

namespace tightfit {
namespace {

/// Corner c of face f as a surface point.
SurfacePoint corner_point(int face, int corner) {
  static constexpr double kU[3] = {0.0, 1.0, 0.0};
  static constexpr double kV[3] = {0.0, 0.0, 1.0};
  return {face, kU[corner], kV[corner]};
}

}  // namespace

Garment make_sleeve(const SleeveParams& p, const LimitSurface& surface, const Points3& control) {
  if (!(p.radius > 0) || !(p.edge_length > 0) || !(p.hoop_scale > 0) || !(p.axial_scale > 0) ||
      !(p.axial_end > p.axial_begin))
    throw InputError("sleeve", "radius, edge length, scales and axial extent must be positive");
  const double width = 2.0 * std::numbers::pi * p.radius * p.hoop_scale;
  const double height = (p.axial_end - p.axial_begin) * p.axial_scale;
  const int nx = std::max(6, static_cast<int>(std::lround(width / p.edge_length)));
  const int ny = std::max(1, static_cast<int>(std::lround(height / p.edge_length)));
  const double dx = width / nx, dy = height / ny;

  std::mt19937 rng(p.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PatternPiece piece;
  piece.name = "sleeve";
  piece.grain = Vec2::UnitY();
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  piece.rest.resize((nx + 1) * (ny + 1), 2);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      Vec2 x(i * dx, j * dy);
      if (i > 0 && i < nx && j > 0 && j < ny)
        x += p.jitter * Vec2(dx * unit(rng), dy * unit(rng)) * 0.5;
      piece.rest.row(id(i, j)) = x;
    }
  piece.triangles.resize(2 * nx * ny, 3);
  int t = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (p.jitter > 0 && unit(rng) < 0) {
        piece.triangles.row(t++) << a, b, d;
        piece.triangles.row(t++) << b, c, d;
      } else {
        piece.triangles.row(t++) << a, b, c;
        piece.triangles.row(t++) << a, c, d;
      }
    }
  for (int i = 0; i < nx; ++i) piece.boundary.push_back(id(i, 0));
  for (int j = 0; j < ny; ++j) piece.boundary.push_back(id(nx, j));
  for (int i = nx; i > 0; --i) piece.boundary.push_back(id(i, ny));
  for (int j = ny; j > 0; --j) piece.boundary.push_back(id(0, j));
  piece.corners = {id(0, 0), id(nx, 0), id(nx, ny), id(0, ny)};

  Seam seam;
  seam.name = "axial seam";
  seam.a.piece = seam.b.piece = 0;
  for (int j = 0; j <= ny; ++j) {
    seam.a.vertices.push_back(id(0, j));
    seam.b.vertices.push_back(id(nx, j));
  }
  Pattern pattern;
  pattern.pieces.push_back(std::move(piece));
  pattern.seams.push_back(std::move(seam));
  for (const auto& [pinned, row, name] : {std::tuple{p.pin_first_ring, 0, "first ring"},
                                          std::tuple{p.pin_last_ring, ny, "last ring"}}) {
    if (!pinned) continue;
    PinnedBoundary pin{name, 0, {}};
    for (int i = 0; i <= nx; ++i) pin.vertices.push_back(id(i, row));
    pattern.pinned.push_back(std::move(pin));
  }
  Garment g = weld_pattern(std::move(pattern));

  // Wrap: piece x → angle, piece y → axial position; project onto the limit surface.
  const Vec3 axis = p.axis.normalized();
  const Vec3 e1 = axis.unitOrthogonal();
  const Vec3 e2 = axis.cross(e1);
  const LimitProjector projector(surface, control);
  g.embedding.assign(g.num_garment_vertices(), SurfacePoint{});
  std::vector<char> done(g.num_garment_vertices(), 0);
  const Points2& rest = g.pattern.pieces[0].rest;
  for (int v = 0; v < rest.rows(); ++v) {
    const int gv = g.topology->pattern_to_garment[v];
    if (done[gv]) continue;
    done[gv] = 1;
    const double s = p.axial_begin + rest(v, 1) / p.axial_scale;
    const double angle = rest(v, 0) / (p.radius * p.hoop_scale) + p.rotation + p.twist * s;
    const Vec3 x = p.center + s * axis + p.radius * (std::cos(angle) * e1 + std::sin(angle) * e2);
    g.embedding[gv] = projector.project(x);
  }
  return g;
}

Garment make_cover(const LimitSurface& surface, const Points3& control, double scale) {
  if (!(scale > 0)) throw InputError("cover", "scale must be positive");
  const int nf = surface.num_faces();
  const int nv = surface.num_control_vertices();
  Pattern pattern;
  pattern.pieces.reserve(nf);
  std::vector<SurfacePoint> vertex_point(nv);
  std::vector<char> seen(nv, 0);
  for (int f = 0; f < nf; ++f) {
    const int* fv = surface.face_vertices(f);
    Vec3 corner[3];
    for (int c = 0; c < 3; ++c) {
      const SurfacePoint sp = corner_point(f, c);
      corner[c] = surface.position(sp, control);
      if (!seen[fv[c]]) {
        seen[fv[c]] = 1;
        vertex_point[fv[c]] = sp;
      }
    }
    // Isometric 2D coordinates of the 3D triangle, scaled.
    const Vec3 a = corner[1] - corner[0], b = corner[2] - corner[0];
    const Vec3 ex = a.normalized();
    const Vec3 ey = (b - b.dot(ex) * ex).normalized();
    PatternPiece piece;
    piece.name = "face " + std::to_string(f);
    piece.rest.resize(3, 2);
    piece.rest << 0, 0, scale * a.norm(), 0, scale * b.dot(ex), scale * b.dot(ey);
    piece.triangles.resize(1, 3);
    piece.triangles << 0, 1, 2;
    piece.boundary = {0, 1, 2};
    piece.corners = {0, 1, 2};
    pattern.pieces.push_back(std::move(piece));
  }
  // Weld by control vertex instead of by seams: garment vertex = control vertex.
  std::vector<int> to_control(static_cast<size_t>(3 * nf));
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c)
      to_control[static_cast<size_t>(3 * f + c)] = surface.face_vertices(f)[c];
  Garment g;
  g.topology =
      std::make_shared<const GarmentTopology>(weld_topology(pattern, std::move(to_control), nv));
  g.pattern = std::move(pattern);
  g.embedding = vertex_point;
  return g;
}

}  // namespace tightfit
