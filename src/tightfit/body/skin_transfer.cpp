#include "tightfit/body/skin_transfer.hpp"

#include <algorithm>
#include <map>
#include <vector>

#include "tightfit/body/surface_distance.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/sparse_cholesky.hpp"

namespace tightfit {
namespace {

constexpr double kInteriorWeightFloor = 1e-4;

/// The rig's weights per rig vertex: (bone index, weight) over the rig's bone order.
struct RigVertexWeights {
  std::vector<std::string> bones;
  std::vector<std::vector<std::pair<int, double>>> per_vertex;
};

RigVertexWeights by_vertex(const SkinWeights& rig) {
  RigVertexWeights out;
  out.per_vertex.resize(static_cast<std::size_t>(rig.vertices.rows()));
  for (const auto& [name, entries] : rig.bones) {
    if (entries.empty()) continue;
    const int b = static_cast<int>(out.bones.size());
    out.bones.push_back(name);
    for (const auto& [v, w] : entries)
      out.per_vertex[static_cast<std::size_t>(v)].emplace_back(b, w);
  }
  return out;
}

/// Barycentric coordinates of `p` (on or near the triangle a b c), clamped to it.
Vec3 barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double det = d00 * d11 - d01 * d01;
  if (!(det > 0.0)) return Vec3(1.0, 0.0, 0.0);  // degenerate rig triangle: its first corner
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  Vec3 l(0.0, (d11 * d20 - d01 * d21) / det, (d00 * d21 - d01 * d20) / det);
  l[0] = 1.0 - l[1] - l[2];
  l = l.cwiseMax(0.0);
  return l / l.sum();
}

}  // namespace

PointWeights transfer_skin_weights(const SkinWeights& rig, const Points3& points,
                                   SkinTransferReport* report) {
  if (rig.faces.rows() == 0) throw InputError(rig.source, "the rig mesh has no faces");
  const RigVertexWeights source = by_vertex(rig);
  const SurfaceDistance tree(TriMesh{rig.vertices, rig.faces});
  PointWeights out;
  out.bones = source.bones;
  SkinTransferReport r;
  std::map<int, double> blend;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vec3 p = points.row(i).transpose();
    Vec3 q;
    const int f = tree.closest_face(p, &q);
    const double distance = (p - q).norm();
    r.max_distance = std::max(r.max_distance, distance);
    r.mean_distance += distance / static_cast<double>(points.rows());
    const Vec3 l = barycentric(q, rig.vertices.row(rig.faces(f, 0)).transpose(),
                               rig.vertices.row(rig.faces(f, 1)).transpose(),
                               rig.vertices.row(rig.faces(f, 2)).transpose());
    blend.clear();
    for (int k = 0; k < 3; ++k)
      for (const auto& [b, w] : source.per_vertex[static_cast<std::size_t>(rig.faces(f, k))])
        blend[b] += l[k] * w;
    std::vector<std::pair<int, double>> entries(blend.begin(), blend.end());
    double total = 0.0;
    for (const auto& e : entries) total += e.second;
    if (!(total > 0.0))
      throw InputError(rig.source, "no skin weight near the point (" + std::to_string(p.x()) +
                                       ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) +
                                       ") m: the rig's nearest triangle has no weighted corner");
    out.add_point(entries);
  }
  if (report) *report = r;
  return out;
}

PointWeights body_skin_weights(const Body& body, const SkinWeights& rig,
                               SkinTransferReport* report) {
  const int ns = body.num_surface_vertices(), n = body.num_vertices();
  const PointWeights surface = transfer_skin_weights(rig, body.surface.vertices, report);
  const int ni = n - ns;
  if (ni == 0) return surface;
  const int nb = static_cast<int>(surface.bones.size());
  // Graph Laplacian of the tet edges, interior rows: L_II W_I = A_IB W_B.
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(n));
  for (int t = 0; t < body.volume.num_tets(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b) neighbours[body.volume.tets(t, a)].push_back(body.volume.tets(t, b));
  std::vector<Triplet> triplets;
  MatX rhs = MatX::Zero(ni, nb);
  for (int v = ns; v < n; ++v) {
    auto& nv = neighbours[v];
    std::sort(nv.begin(), nv.end());
    nv.erase(std::unique(nv.begin(), nv.end()), nv.end());
    triplets.emplace_back(v - ns, v - ns, static_cast<double>(nv.size()));
    for (int u : nv) {
      if (u >= ns) {
        triplets.emplace_back(v - ns, u - ns, -1.0);
        continue;
      }
      for (int k = surface.offsets[u]; k < surface.offsets[u + 1]; ++k)
        rhs(v - ns, surface.bone[k]) += surface.weight[k];
    }
  }
  SparseMatrix L(ni, ni);
  L.setFromTriplets(triplets.begin(), triplets.end());
  SparseCholesky cholesky;
  if (!cholesky.factorize(L))
    throw InputError("body", "the tet mesh has interior vertices not connected to the surface");
  const MatX interior = cholesky.solve_columns(rhs);
  PointWeights out = surface;
  std::vector<std::pair<int, double>> entries;
  for (int i = 0; i < ni; ++i) {
    entries.clear();
    for (int b = 0; b < nb; ++b)
      if (interior(i, b) >= kInteriorWeightFloor) entries.emplace_back(b, interior(i, b));
    if (entries.empty()) {  // no weight above the floor: the largest one
      Eigen::Index b = 0;
      interior.row(i).maxCoeff(&b);
      entries.emplace_back(static_cast<int>(b), 1.0);
    }
    out.add_point(entries);
  }
  return out;
}

}  // namespace tightfit
