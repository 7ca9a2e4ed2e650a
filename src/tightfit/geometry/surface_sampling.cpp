#include "tightfit/geometry/surface_sampling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tightfit/geometry/mesh_measures.hpp"

namespace tightfit {
namespace {

/// Parts an edge of this length is divided into (≥ 1).
std::int64_t edge_parts(double length, double spacing) {
  const double parts = std::ceil(length / spacing);
  return parts > 1.0 ? static_cast<std::int64_t>(std::min(parts, 1e9)) : 1;
}

struct SampledEdge {
  int a, b;  // a < b
  int face;  // a face with non-zero area on it
};

struct Layout {
  std::vector<int> vertex_face;    // a face with non-zero area using the vertex, or −1
  std::vector<SampledEdge> edges;  // distinct edges of those faces
  std::vector<int> faces;          // faces with non-zero area
};

Layout layout_of(const TriMesh& mesh) {
  Layout l;
  l.vertex_face.assign(static_cast<size_t>(mesh.num_vertices()), -1);
  const VecX areas = face_areas(mesh);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (!(areas[f] > 0.0)) continue;
    l.faces.push_back(f);
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.faces(f, c), b = mesh.faces(f, (c + 1) % 3);
      if (l.vertex_face[static_cast<size_t>(a)] < 0) l.vertex_face[static_cast<size_t>(a)] = f;
      l.edges.push_back({std::min(a, b), std::max(a, b), f});
    }
  }
  auto key = [](const SampledEdge& e) { return std::pair(e.a, e.b); };
  std::stable_sort(l.edges.begin(), l.edges.end(),
                   [&](const SampledEdge& x, const SampledEdge& y) { return key(x) < key(y); });
  l.edges.erase(
      std::unique(l.edges.begin(), l.edges.end(),
                  [&](const SampledEdge& x, const SampledEdge& y) { return key(x) == key(y); }),
      l.edges.end());
  return l;
}

double edge_length(const TriMesh& mesh, int a, int b) {
  return (mesh.vertices.row(a) - mesh.vertices.row(b)).norm();
}

std::int64_t face_level(const TriMesh& mesh, int f, double spacing) {
  std::int64_t n = 1;
  for (int c = 0; c < 3; ++c)
    n = std::max(
        n, edge_parts(edge_length(mesh, mesh.faces(f, c), mesh.faces(f, (c + 1) % 3)), spacing));
  return n;
}

/// Phong tessellation with α = ½ at the flat point q = Σ w_i p_i (surface_sampling.hpp).
template <int N>
Vec3 phong_point(const std::array<Vec3, N>& p, const std::array<Vec3, N>& n,
                 const std::array<double, N>& w) {
  Vec3 flat = Vec3::Zero();
  for (int i = 0; i < N; ++i) flat += w[i] * p[i];
  Vec3 projected = Vec3::Zero();
  for (int i = 0; i < N; ++i) projected += w[i] * (flat - (flat - p[i]).dot(n[i]) * n[i]);
  return 0.5 * (flat + projected);
}

void check_spacing(double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw std::invalid_argument("sample_surface: spacing must be positive and finite");
}

}  // namespace

std::int64_t count_surface_samples(const TriMesh& mesh, double spacing) {
  check_spacing(spacing);
  const Layout l = layout_of(mesh);
  double count = static_cast<double>(
      std::count_if(l.vertex_face.begin(), l.vertex_face.end(), [](int f) { return f >= 0; }));
  for (const SampledEdge& e : l.edges)
    count += static_cast<double>(edge_parts(edge_length(mesh, e.a, e.b), spacing) - 1);
  for (int f : l.faces) {
    const double n = static_cast<double>(face_level(mesh, f, spacing));
    count += (n - 1.0) * (n - 2.0) / 2.0;
  }
  return static_cast<std::int64_t>(std::min(count, 9e18));
}

OrientedPoints sample_surface(const TriMesh& mesh, double spacing) {
  const std::int64_t count = count_surface_samples(mesh, spacing);
  const Layout l = layout_of(mesh);
  const Points3 vertex_normal = vertex_normals(mesh);
  const Points3 face_normal = face_normals(mesh);
  OrientedPoints out;
  out.points.resize(count, 3);
  out.normals.resize(count, 3);
  Eigen::Index next = 0;
  // Barycentric combination of vertices and their normals; the normal falls back to the
  // face's when the interpolated one vanishes (opposite vertex normals).
  auto add = [&](const Vec3& point, const Vec3& normal, const Vec3& fallback) {
    out.points.row(next) = point.transpose();
    const double len = normal.norm();
    out.normals.row(next) = (len > 1e-12 ? Vec3(normal / len) : fallback).transpose();
    ++next;
  };
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (const int f = l.vertex_face[static_cast<size_t>(v)]; f >= 0)
      add(mesh.vertices.row(v).transpose(), vertex_normal.row(v).transpose(),
          face_normal.row(f).transpose());
  for (const SampledEdge& e : l.edges) {
    const int a = e.a, b = e.b;
    const std::int64_t n = edge_parts(edge_length(mesh, a, b), spacing);
    const Vec3 pa = mesh.vertices.row(a).transpose(), pb = mesh.vertices.row(b).transpose();
    const Vec3 na = vertex_normal.row(a).transpose(), nb = vertex_normal.row(b).transpose();
    for (std::int64_t i = 1; i < n; ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(n);
      add(phong_point<2>({pa, pb}, {na, nb}, {1.0 - t, t}), (1.0 - t) * na + t * nb,
          face_normal.row(e.face).transpose());
    }
  }
  for (int f : l.faces) {
    const std::int64_t n = face_level(mesh, f, spacing);
    const int ia = mesh.faces(f, 0), ib = mesh.faces(f, 1), ic = mesh.faces(f, 2);
    const Vec3 pa = mesh.vertices.row(ia).transpose(), pb = mesh.vertices.row(ib).transpose(),
               pc = mesh.vertices.row(ic).transpose();
    const Vec3 na = vertex_normal.row(ia).transpose(), nb = vertex_normal.row(ib).transpose(),
               nc = vertex_normal.row(ic).transpose();
    const Vec3 fallback = face_normal.row(f).transpose();
    const double inv = 1.0 / static_cast<double>(n);
    for (std::int64_t i = 1; i < n; ++i)
      for (std::int64_t j = 1; i + j < n; ++j) {
        const double wa = static_cast<double>(i) * inv, wb = static_cast<double>(j) * inv;
        const double wc = 1.0 - wa - wb;
        add(phong_point<3>({pa, pb, pc}, {na, nb, nc}, {wa, wb, wc}), wa * na + wb * nb + wc * nc,
            fallback);
      }
  }
  return out;
}

}  // namespace tightfit
