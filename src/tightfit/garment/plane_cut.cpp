#include "tightfit/garment/plane_cut.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

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

/// A cutting surface as a level set: value(x) = 0 on it, ≈ the signed distance (m) near
/// it, positive on its "+" side.
struct Cutter {
  std::function<double(const Vec3&)> value;
  std::function<Vec3(const Vec3&)> gradient;
  bool planar = false;  ///< value is exactly affine (a plane)
};

Cutter plane_cutter(const LayoutPlane& plane) {
  return {[plane](const Vec3& x) { return plane.distance(x); }, [plane](const Vec3&) { return plane.normal; },
          true};
}

Cutter opening_cutter(const LayoutOpening& opening) {
  return {[opening](const Vec3& x) { return opening.level(x); },
          [opening](const Vec3& x) { return opening.level_gradient(x); }, false};
}

/// The point of edge a→b where the cutter's value is zero, starting from the linear
/// interpolation of the end values (exact for planes, Newton along the edge otherwise).
Vec3 edge_crossing(const Cutter& cut, const Vec3& a, const Vec3& b, double da, double db) {
  double t = da / (da - db);
  if (cut.planar) {
    const Vec3 p = a + t * (b - a);
    return p - cut.value(p) * cut.gradient(p);  // exactly on the plane up to rounding
  }
  for (int it = 0; it < 20; ++it) {
    const Vec3 p = a + t * (b - a);
    const double f = cut.value(p), slope = cut.gradient(p).dot(b - a);
    if (slope == 0.0) break;
    const double step = f / slope;
    t = std::clamp(t - step, 0.0, 1.0);
    if (std::abs(step) < 1e-14) break;
  }
  return a + t * (b - a);
}

void cut_one(Work& w, const Cutter& cut, int k, double eps, double snap_fraction) {
  const int nv = static_cast<int>(w.x.size());
  std::vector<double> d(nv);
  for (int v = 0; v < nv; ++v) {
    d[v] = cut.value(w.x[v]);
    if (std::abs(d[v]) <= eps) {
      d[v] = 0.0;
      w.on_plane[k][v] = 1;
    }
  }
  // Snap vertices that would leave a sliver next to a new vertex.
  if (snap_fraction > 0.0) {
    const Points3 normals = vertex_normals(to_points(w.x), w.faces);
    std::vector<char> snap(nv, 0);
    for (const auto& f : w.faces)
      for (int i = 0; i < 3; ++i) {
        const int a = f[i], b = f[(i + 1) % 3];
        if (d[a] * d[b] >= 0.0) continue;
        const double t = d[a] / (d[a] - d[b]);
        if (t < snap_fraction && !w.locked(a)) snap[a] = 1;
        if (t > 1.0 - snap_fraction && !w.locked(b)) snap[b] = 1;
      }
    for (int v = 0; v < nv; ++v) {
      if (!snap[v]) continue;
      const Vec3 n = normals.row(v).transpose();
      const Vec3 g = cut.gradient(w.x[v]);
      const Vec3 dir = g - g.dot(n) * n;
      const double along = g.dot(dir);
      if (!(along >= 0.25 * g.squaredNorm())) continue;  // cut nearly tangent to the surface here
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
  // One new vertex per crossed edge.
  std::map<std::pair<int, int>, int> split;
  auto split_vertex = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = split.find(key);
    if (it != split.end()) return it->second;
    const Vec3 p = edge_crossing(cut, w.x[a], w.x[b], d[a], d[b]);
    const int id = static_cast<int>(w.x.size());
    w.x.push_back(p);
    for (size_t j = 0; j < w.on_plane.size(); ++j)
      w.on_plane[j].push_back(static_cast<int>(j) == k || (w.on_plane[j][a] && w.on_plane[j][b]));
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
                                   const std::vector<LayoutOpening>& openings, double snap_fraction) {
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
  double diag = 0.0;
  if (nv > 0)
    diag = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
  const double eps = 1e-10 * std::max(diag, 1e-3);
  for (size_t k = 0; k < cutters.size(); ++k)
    cut_one(w, cutters[k], static_cast<int>(k), eps, snap_fraction);

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
      for (int i = 0; i < 3; ++i)
        if (!out.on_plane[k][w.faces[f][i]]) s += cutters[k].value(w.x[w.faces[f][i]]);
      out.side[k][f] = s < 0.0 ? -1 : 1;
    }
  return out;
}

}  // namespace tightfit
