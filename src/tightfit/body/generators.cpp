#include "tightfit/body/generators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

namespace tightfit {
namespace {

/// Height of an equilateral triangle relative to its edge: spacing of rings.
const double kRowHeight = std::sqrt(3.0) / 2.0;

/// One ring of vertices around the axis: axial coordinate s, radius r (0 for a pole,
/// which then has one vertex), vertex count n, angle of the first vertex.
struct Ring {
  double s;
  double r;
  int n;
  double phase;
};

/// Orthonormal frame (e1, e2, axis) with e1 × e2 = axis.
struct Frame {
  Vec3 e1, e2, axis;
};

Frame make_frame(const Vec3& axis_in) {
  const double norm = axis_in.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw std::invalid_argument("cylinder axis must be a non-zero vector");
  Frame f;
  f.axis = axis_in / norm;
  const Vec3 helper = std::abs(f.axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  f.e1 = (helper - helper.dot(f.axis) * f.axis).normalized();
  f.e2 = f.axis.cross(f.e1);
  return f;
}

int ring_count(double r, double h) {
  return std::max(3, static_cast<int>(std::lround(2.0 * std::numbers::pi * r / h)));
}

/// Triangulates the band between ring A (vertex ids a, angles increasing) and ring B
/// (next along the axis, or inwards on a top disc). Orientation: outward for rings
/// ordered from the bottom pole to the top pole (see generators.hpp).
void stitch_rings(const Ring& ra, const std::vector<int>& a, const Ring& rb,
                  const std::vector<int>& b, std::vector<std::array<int, 3>>& tris) {
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  if (na == 1) {  // bottom pole fan
    for (int j = 0; j < nb; ++j) tris.push_back({a[0], b[(j + 1) % nb], b[j]});
    return;
  }
  if (nb == 1) {  // top pole fan
    for (int i = 0; i < na; ++i) tris.push_back({a[i], a[(i + 1) % na], b[0]});
    return;
  }
  // Start B at the vertex closest in angle to A's first vertex; walk both rings in
  // angle order, always advancing the ring whose next vertex comes first.
  const double da = 2.0 * std::numbers::pi / na, db = 2.0 * std::numbers::pi / nb;
  double rel =
      std::remainder(rb.phase - ra.phase, db);  // B's first angle near A[0], in (-db/2, db/2]
  const int shift = static_cast<int>(std::lround((ra.phase + rel - rb.phase) / db));
  const int jb0 = ((shift % nb) + nb) % nb;
  int ca = 0, cb = 0;
  while (ca < na || cb < nb) {
    const double next_a = (ca + 1) * da;
    const double next_b = rel + (cb + 1) * db;
    const int ia = ca % na, ib = (jb0 + cb) % nb;
    if (cb == nb || (ca < na && next_a <= next_b)) {
      tris.push_back({a[ia], a[(ia + 1) % na], b[ib]});
      ++ca;
    } else {
      tris.push_back({a[ia], b[(ib + 1) % nb], b[ib]});
      ++cb;
    }
  }
}

TriMesh mesh_from_rings(const std::vector<Ring>& rings, const Vec3& center, const Frame& frame) {
  std::vector<std::vector<int>> ids(rings.size());
  std::vector<Vec3> points;
  for (size_t k = 0; k < rings.size(); ++k) {
    const Ring& ring = rings[k];
    for (int j = 0; j < ring.n; ++j) {
      const double phi = ring.phase + 2.0 * std::numbers::pi * j / ring.n;
      ids[k].push_back(static_cast<int>(points.size()));
      points.push_back(center + ring.s * frame.axis +
                       ring.r * (std::cos(phi) * frame.e1 + std::sin(phi) * frame.e2));
    }
  }
  std::vector<std::array<int, 3>> tris;
  for (size_t k = 0; k + 1 < rings.size(); ++k)
    stitch_rings(rings[k], ids[k], rings[k + 1], ids[k + 1], tris);
  TriMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = points[i];
  mesh.faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t f = 0; f < tris.size(); ++f)
    for (int c = 0; c < 3; ++c) mesh.faces(static_cast<Eigen::Index>(f), c) = tris[f][c];
  return mesh;
}

double resolved_edge(double edge_length, double radius) {
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("radius must be positive");
  if (edge_length == 0.0) return default_generator_edge_length(radius);
  if (!(edge_length > 0.0) || !std::isfinite(edge_length))
    throw std::invalid_argument("edge length must be positive");
  return edge_length;
}

}  // namespace

double default_generator_edge_length(double radius) {
  return radius * 2.0 * std::numbers::pi / 48.0;
}

TriMesh cylinder_surface(const CylinderParams& p, LimitFitResult* fit) {
  const double h = resolved_edge(p.edge_length, p.radius);
  if (!(p.length >= 0.0) || !std::isfinite(p.length))
    throw std::invalid_argument("cylinder length must be non-negative");
  if (p.caps == CapStyle::kFlat && !(p.length > 0.0))
    throw std::invalid_argument("a cylinder with flat caps needs a positive length");
  const Frame frame = make_frame(p.axis);
  const double R = p.radius, half = 0.5 * p.length;
  const int n_side = ring_count(R, h);
  const int n_rows =
      p.length > 0.0 ? std::max(1, static_cast<int>(std::lround(p.length / (kRowHeight * h)))) : 0;

  std::vector<Ring> side;
  for (int k = 0; k <= n_rows; ++k)
    side.push_back({n_rows > 0 ? -half + p.length * k / n_rows : 0.0, R, n_side,
                    (k % 2) * std::numbers::pi / n_side});

  // Cap rings from the rim (exclusive) to the pole (inclusive), as (axial offset beyond
  // the rim, radius) pairs.
  std::vector<std::pair<double, double>> cap;
  if (p.caps == CapStyle::kRound) {
    const int m =
        std::max(2, static_cast<int>(std::lround(0.5 * std::numbers::pi * R / (kRowHeight * h))));
    for (int i = 1; i <= m; ++i) {
      const double theta = 0.5 * std::numbers::pi * i / m;
      cap.emplace_back(R * std::sin(theta), i == m ? 0.0 : R * std::cos(theta));
    }
  } else {
    const int m = std::max(1, static_cast<int>(std::lround(R / (kRowHeight * h))));
    for (int i = 1; i <= m; ++i) cap.emplace_back(0.0, i == m ? 0.0 : R * (m - i) / m);
  }
  auto cap_ring = [&](double offset, double r, double s_sign, double prev_phase, int prev_n) {
    const int n = r > 0.0 ? ring_count(r, h) : 1;
    return Ring{s_sign * (half + offset), r, n,
                prev_phase + std::numbers::pi / std::max(prev_n, n)};
  };

  std::vector<Ring> rings;
  {  // bottom cap, from the pole up to the rim
    std::vector<Ring> bottom;
    double phase = side.front().phase;
    int prev_n = n_side;
    for (const auto& [offset, r] : cap) {
      bottom.push_back(cap_ring(offset, r, -1.0, phase, prev_n));
      phase = bottom.back().phase;
      prev_n = bottom.back().n;
    }
    rings.assign(bottom.rbegin(), bottom.rend());
  }
  rings.insert(rings.end(), side.begin(), side.end());
  {
    double phase = side.back().phase;
    int prev_n = n_side;
    for (const auto& [offset, r] : cap) {
      rings.push_back(cap_ring(offset, r, 1.0, phase, prev_n));
      phase = rings.back().phase;
      prev_n = rings.back().n;
    }
  }
  TriMesh mesh = mesh_from_rings(rings, p.center, frame);
  if (p.fit_limit) {
    const LimitFitResult r =
        fit_loop_limit(mesh, [&p](const Vec3& x) { return project_to_cylinder(p, x); });
    if (fit) *fit = r;
  }
  return mesh;
}

TriMesh sphere_surface(const SphereParams& p, LimitFitResult* fit) {
  const double h = resolved_edge(p.edge_length, p.radius);
  // Unit icosahedron.
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> corners = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                               {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                               {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (auto& c : corners) c.normalize();
  const std::vector<std::array<int, 3>> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  const double ico_edge = (corners[0] - corners[1]).norm() * p.radius;
  // Projection stretches the middle of each face by about 1.2: compensate halfway.
  const int k = std::max(1, static_cast<int>(std::ceil(ico_edge * 1.1 / h - 0.5)));

  std::vector<Vec3> points(corners.begin(), corners.end());
  std::map<std::pair<int, int>, std::vector<int>> edge_points;  // (lo, hi) → ids from lo to hi
  auto edge_point = [&](int u, int v, int step) {               // point `step` of k along u→v
    const int lo = std::min(u, v), hi = std::max(u, v);
    auto it = edge_points.find({lo, hi});
    if (it == edge_points.end()) {
      std::vector<int> ids;
      for (int s = 1; s < k; ++s) {
        ids.push_back(static_cast<int>(points.size()));
        points.push_back(corners[lo] + (corners[hi] - corners[lo]) * (double(s) / k));
      }
      it = edge_points.emplace(std::make_pair(lo, hi), std::move(ids)).first;
    }
    return u == lo ? it->second[step - 1] : it->second[k - step - 1];
  };
  std::vector<std::array<int, 3>> tris;
  for (const auto& f : faces) {
    const int a = f[0], b = f[1], c = f[2];
    // Grid point (i, j) = a + i/k (b − a) + j/k (c − a), i + j ≤ k.
    std::vector<std::vector<int>> id(k + 1, std::vector<int>(k + 1, -1));
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        if (i == 0 && j == 0)
          id[i][j] = a;
        else if (i == k)
          id[i][j] = b;
        else if (j == k)
          id[i][j] = c;
        else if (j == 0)
          id[i][j] = edge_point(a, b, i);
        else if (i == 0)
          id[i][j] = edge_point(a, c, j);
        else if (i + j == k)
          id[i][j] = edge_point(b, c, j);
        else {
          id[i][j] = static_cast<int>(points.size());
          points.push_back(corners[a] + (corners[b] - corners[a]) * (double(i) / k) +
                           (corners[c] - corners[a]) * (double(j) / k));
        }
      }
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        tris.push_back({id[i][j], id[i + 1][j], id[i][j + 1]});
        if (i + j + 1 < k) tris.push_back({id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]});
      }
  }
  TriMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = p.center + p.radius * points[i].normalized();
  mesh.faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t f = 0; f < tris.size(); ++f)
    for (int c = 0; c < 3; ++c) mesh.faces(static_cast<Eigen::Index>(f), c) = tris[f][c];
  if (p.fit_limit) {
    const LimitFitResult r =
        fit_loop_limit(mesh, [&p](const Vec3& x) { return project_to_sphere(p, x); });
    if (fit) *fit = r;
  }
  return mesh;
}

namespace {
double core_edge(double body_edge, double body_radius, double core_radius) {
  if (!(core_radius > 0.0 && core_radius < body_radius))
    throw std::invalid_argument("the core radius must be positive and smaller than the body's");
  return std::min(resolved_edge(body_edge, body_radius),
                  2.0 * std::numbers::pi * core_radius / 32.0);
}
}  // namespace

CylinderParams cylinder_core(const CylinderParams& body, double core_radius) {
  CylinderParams core = body;
  core.edge_length = core_edge(body.edge_length, body.radius, core_radius);
  core.radius = core_radius;
  core.fit_limit = false;
  if (body.caps == CapStyle::kFlat) {
    core.length = body.length - 2.0 * (body.radius - core_radius);
    if (!(core.length > 0.0))
      throw std::invalid_argument(
          "the flat-capped core would have no length: use a larger core radius");
  }
  return core;
}

SphereParams sphere_core(const SphereParams& body, double core_radius) {
  SphereParams core = body;
  core.edge_length = core_edge(body.edge_length, body.radius, core_radius);
  core.radius = core_radius;
  core.fit_limit = false;
  return core;
}

Vec3 project_to_cylinder(const CylinderParams& p, const Vec3& x) {
  const Frame frame = make_frame(p.axis);
  const double half = 0.5 * p.length;
  const Vec3 q = x - p.center;
  const double z = q.dot(frame.axis);
  Vec3 radial = q - z * frame.axis;
  const double rho = radial.norm();
  const Vec3 dir = rho > 0.0 ? Vec3(radial / rho) : frame.e1;
  if (p.caps == CapStyle::kRound) {
    const double t = std::clamp(z, -half, half);
    const Vec3 d = q - t * frame.axis;
    const double dn = d.norm();
    return p.center + t * frame.axis + p.radius * (dn > 0.0 ? Vec3(d / dn) : dir);
  }
  const Vec3 on_side = p.center + std::clamp(z, -half, half) * frame.axis + p.radius * dir;
  const Vec3 on_disc =
      p.center + (z >= 0.0 ? half : -half) * frame.axis + std::min(rho, p.radius) * dir;
  return (x - on_side).squaredNorm() <= (x - on_disc).squaredNorm() ? on_side : on_disc;
}

Vec3 project_to_sphere(const SphereParams& p, const Vec3& x) {
  const Vec3 d = x - p.center;
  const double n = d.norm();
  return p.center + p.radius * (n > 0.0 ? Vec3(d / n) : Vec3::UnitZ());
}

double cylinder_area(const CylinderParams& p) {
  const double side = 2.0 * std::numbers::pi * p.radius * p.length;
  return side + (p.caps == CapStyle::kRound ? 4.0 : 2.0) * std::numbers::pi * p.radius * p.radius;
}

double sphere_area(const SphereParams& p) { return 4.0 * std::numbers::pi * p.radius * p.radius; }

}  // namespace tightfit
