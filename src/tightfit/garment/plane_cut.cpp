#include "tightfit/garment/plane_cut.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

namespace tightfit {
namespace {

Points3 vertex_normals(const Points3& x, const std::vector<std::array<int, 3>>& faces) {
  Points3 n = Points3::Zero(x.rows(), 3);
  for (const auto& f : faces) {
    const Vec3 a = x.row(f[0]), b = x.row(f[1]), c = x.row(f[2]);
    const Vec3 fn = (b - a).cross(c - a);  // area weighted
    for (int k = 0; k < 3; ++k) n.row(f[k]) += fn.transpose();
  }
  for (Eigen::Index i = 0; i < n.rows(); ++i) {
    const double len = n.row(i).norm();
    if (len > 0) n.row(i) /= len;
  }
  return n;
}

struct Work {
  std::vector<Vec3> x;
  std::vector<std::array<int, 3>> faces;
  std::vector<int> parent;
  std::vector<std::vector<char>> on_plane;
  /// Per cut: the bone region's field value per vertex (linear along every edge); empty
  /// for planes.
  std::vector<std::vector<double>> field;

  bool locked(int v) const {
    for (const auto& flags : on_plane)
      if (flags[v]) return true;
    return false;
  }
};

Points3 to_points(const std::vector<Vec3>& x) {
  Points3 p(static_cast<Eigen::Index>(x.size()), 3);
  for (size_t i = 0; i < x.size(); ++i) p.row(static_cast<Eigen::Index>(i)) = x[i].transpose();
  return p;
}

/// A cutting surface. Planes and openings are level sets: value(x) = 0 on them, ≈ the
/// signed distance (m) near them, positive on their "+" side; a bone region's values
/// are its per-vertex field (Work::field).
struct Cutter {
  std::function<double(const Vec3&)> value;
  std::function<Vec3(const Vec3&)> gradient;
  bool planar = false;  ///< value is exactly affine (a plane)
  bool from_field =
      false;  ///< values from the field (bone regions, local planes), linear along every edge
};

Cutter plane_cutter(const LayoutPlane& plane) {
  Cutter c{[plane](const Vec3& x) { return plane.distance(x); },
           [plane](const Vec3&) { return plane.normal; }, true, plane.is_field()};
  return c;
}

Cutter opening_cutter(const LayoutOpening& opening) {
  return {[opening](const Vec3& x) { return opening.level(x); },
          [opening](const Vec3& x) { return opening.level_gradient(x); }, false, false};
}

/// The parameter t of the point of edge a→b where a level-set cutter is zero: the linear
/// interpolation of the end values for planes, refined by Newton along the edge for
/// curved cutters (the point then lies on the surface to round-off).
double edge_crossing(const Cutter& cut, const Vec3& a, const Vec3& b, double da, double db) {
  double t = da / (da - db);
  if (cut.planar) return t;
  for (int it = 0; it < 20; ++it) {
    const Vec3 p = a + t * (b - a);
    const double slope = cut.gradient(p).dot(b - a);
    if (slope == 0.0) break;
    const double step = cut.value(p) / slope;
    t = std::clamp(t - step, 0.0, 1.0);
    if (std::abs(step) < 1e-14) break;
  }
  return t;
}

/// Cuts along plane or opening k, or along the ½ iso-line of bone region k's field
/// (eps: the tolerance of "on the cut", m for planes and openings, dimensionless for
/// fields).
void cut_one(Work& w, const Cutter& cut, int k, double eps, double snap_fraction) {
  const int nv = static_cast<int>(w.x.size());
  const bool is_field = cut.from_field;
  std::vector<double>* field = is_field ? &w.field[k] : nullptr;
  std::vector<double> d(nv);
  for (int v = 0; v < nv; ++v) {
    d[v] = is_field ? (*field)[v] : cut.value(w.x[v]);
    if (std::abs(d[v]) <= eps) {
      d[v] = 0.0;
      w.on_plane[k][v] = 1;
    }
  }
  if (is_field)
    for (int v = 0; v < nv; ++v)
      if (w.on_plane[k][v]) (*field)[v] = 0.0;
  // Snap vertices that would leave a sliver next to a new vertex.
  if (snap_fraction > 0.0) {
    // Per vertex: its nearest crossing along its edges (fraction of the edge, other end).
    std::vector<std::pair<double, int>> nearest(nv, {snap_fraction, -1});
    for (const auto& f : w.faces)
      for (int i = 0; i < 3; ++i) {
        const int a = f[i], b = f[(i + 1) % 3];
        if (d[a] * d[b] >= 0.0) continue;
        const double t = d[a] / (d[a] - d[b]);
        if (t < nearest[a].first && !w.locked(a)) nearest[a] = {t, b};
        if (1.0 - t < nearest[b].first && !w.locked(b)) nearest[b] = {1.0 - t, a};
      }
    if (is_field) {
      // The vertex moves along that edge onto the iso-line and every field with it
      // (fields are linear along edges), so that cuts whose iso-lines coincide there (a
      // bone region and a divider of the same bones' edge) stay together.
      const std::vector<Vec3> x0 = w.x;
      const std::vector<std::vector<double>> f0 = w.field;
      for (int v = 0; v < nv; ++v) {
        const auto [t, u] = nearest[v];
        if (u < 0) continue;
        w.x[v] = x0[v] + t * (x0[u] - x0[v]);
        for (size_t j = 0; j < w.field.size(); ++j)
          if (!w.field[j].empty()) w.field[j][v] = f0[j][v] + t * (f0[j][u] - f0[j][v]);
        (*field)[v] = 0.0;
        d[v] = 0.0;
        w.on_plane[k][v] = 1;
      }
    } else {
      const Points3 normals = vertex_normals(to_points(w.x), w.faces);
      for (int v = 0; v < nv; ++v) {
        if (nearest[v].second < 0) continue;
        const Vec3 n = normals.row(v).transpose();
        const Vec3 g = cut.gradient(w.x[v]);
        const Vec3 dir = g - g.dot(n) * n;
        if (!(g.dot(dir) >= 0.25 * g.squaredNorm()))
          continue;  // cut nearly tangent to the surface here
        // Along the tangent direction onto the cut (one step for a plane, Newton otherwise).
        Vec3 x = w.x[v];
        for (int it = 0; it < (cut.planar ? 1 : 10); ++it) {
          const double slope = cut.gradient(x).dot(dir);
          if (!(slope > 0)) break;
          x -= (cut.value(x) / slope) * dir;
        }
        w.x[v] = x;
        d[v] = 0.0;
        w.on_plane[k][v] = 1;
      }
    }
  }
  // One new vertex per crossed edge.
  std::map<std::pair<int, int>, int> split;
  auto split_vertex = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = split.find(key);
    if (it != split.end()) return it->second;
    const double t =
        is_field ? d[a] / (d[a] - d[b]) : edge_crossing(cut, w.x[a], w.x[b], d[a], d[b]);
    Vec3 p = w.x[a] + t * (w.x[b] - w.x[a]);
    if (!is_field && cut.planar)
      p -= cut.value(p) * cut.gradient(p);  // exactly on the plane up to rounding
    const int id = static_cast<int>(w.x.size());
    w.x.push_back(p);
    for (size_t j = 0; j < w.on_plane.size(); ++j)
      w.on_plane[j].push_back(static_cast<int>(j) == k || (w.on_plane[j][a] && w.on_plane[j][b]));
    for (auto& values : w.field)  // fields are linear along the edge
      if (!values.empty()) values.push_back(values[a] + t * (values[b] - values[a]));
    if (is_field) field->back() = 0.0;
    d.push_back(0.0);
    split.emplace(key, id);
    return id;
  };
  std::vector<std::array<int, 3>> faces;
  std::vector<int> parent;
  faces.reserve(w.faces.size());
  for (size_t fi = 0; fi < w.faces.size(); ++fi) {
    const auto f = w.faces[fi];
    int crossed = 0;
    for (int i = 0; i < 3; ++i)
      if (d[f[i]] * d[f[(i + 1) % 3]] < 0.0) ++crossed;
    auto emit = [&](int a, int b, int c) {
      faces.push_back({a, b, c});
      parent.push_back(w.parent[fi]);
    };
    if (crossed == 0) {
      emit(f[0], f[1], f[2]);
    } else if (crossed == 1) {
      // The corner opposite the crossed edge lies on the plane: split in two.
      for (int i = 0; i < 3; ++i) {
        const int a = f[i], b = f[(i + 1) % 3], c = f[(i + 2) % 3];
        if (d[a] * d[b] < 0.0) {
          const int m = split_vertex(a, b);
          emit(a, m, c);
          emit(m, b, c);
        }
      }
    } else {
      // Corner i is alone on its side: edges (i, i+1) and (i+2, i) are crossed.
      for (int i = 0; i < 3; ++i) {
        const int a = f[i], b = f[(i + 1) % 3], c = f[(i + 2) % 3];
        if (d[a] * d[b] < 0.0 && d[c] * d[a] < 0.0) {
          const int mab = split_vertex(a, b);
          const int mca = split_vertex(c, a);
          emit(a, mab, mca);
          // Quad mab, b, c, mca: split along its shorter diagonal.
          if ((w.x[mab] - w.x[c]).squaredNorm() <= (w.x[b] - w.x[mca]).squaredNorm()) {
            emit(mab, b, c);
            emit(mab, c, mca);
          } else {
            emit(mab, b, mca);
            emit(b, c, mca);
          }
        }
      }
    }
  }
  w.faces = std::move(faces);
  w.parent = std::move(parent);
}

}  // namespace

CutMesh cut_by_planes(const TriMesh& mesh, const std::vector<LayoutPlane>& planes,
                      double snap_fraction) {
  return cut_by_planes_and_openings(mesh, planes, {}, snap_fraction);
}

CutMesh cut_by_planes_and_openings(const TriMesh& mesh, const std::vector<LayoutPlane>& planes,
                                   const std::vector<LayoutOpening>& openings,
                                   double snap_fraction) {
  std::vector<Cutter> cutters;
  for (const auto& plane : planes) cutters.push_back(plane_cutter(plane));
  for (const auto& opening : openings) cutters.push_back(opening_cutter(opening));
  Work w;
  const int nv = mesh.num_vertices();
  w.x.resize(nv);
  for (int v = 0; v < nv; ++v) w.x[v] = mesh.vertices.row(v).transpose();
  w.faces.resize(mesh.num_faces());
  w.parent.resize(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    w.faces[f] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
    w.parent[f] = f;
  }
  w.on_plane.assign(cutters.size(), std::vector<char>(nv, 0));
  w.field.resize(cutters.size());
  for (size_t k = 0; k < planes.size(); ++k) {
    const LayoutPlane& plane = planes[k];
    if (plane.anchor || plane.along_bone)
      throw std::invalid_argument(
          "cut_by_planes: plane \"" + plane.name +
          "\" is anchored on the skeleton and not resolved (layout_anchors.hpp)");
    if (!plane.is_field()) continue;
    if (plane.field.size() != static_cast<size_t>(nv))
      throw std::invalid_argument("cut_by_planes: bone region or local plane \"" + plane.name +
                                  "\" is not resolved on this mesh (layout_anchors.hpp)");
    w.field[k] = plane.field;
  }
  double diag = 0.0;
  if (nv > 0)
    diag = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
  const double eps = 1e-10 * std::max(diag, 1e-3);
  for (size_t k = 0; k < cutters.size(); ++k)
    cut_one(w, cutters[k], static_cast<int>(k), cutters[k].from_field ? 1e-12 : eps, snap_fraction);

  CutMesh out;
  out.mesh.vertices = to_points(w.x);
  out.mesh.faces.resize(static_cast<Eigen::Index>(w.faces.size()), 3);
  for (size_t f = 0; f < w.faces.size(); ++f)
    for (int i = 0; i < 3; ++i) out.mesh.faces(static_cast<Eigen::Index>(f), i) = w.faces[f][i];
  out.parent_face = std::move(w.parent);
  out.on_plane = std::move(w.on_plane);
  out.side.assign(cutters.size(), std::vector<signed char>(w.faces.size(), 1));
  for (size_t k = 0; k < cutters.size(); ++k)
    for (size_t f = 0; f < w.faces.size(); ++f) {
      double s = 0.0;
      for (int i = 0; i < 3; ++i) {
        const int v = w.faces[f][i];
        if (!out.on_plane[k][v]) s += w.field[k].empty() ? cutters[k].value(w.x[v]) : w.field[k][v];
      }
      out.side[k][f] = s < 0.0 ? -1 : 1;
    }
  return out;
}

}  // namespace tightfit
