#include "tightfit/geometry/mesh_measures.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace tightfit {

namespace {

Vec3 corner(const Points3& v, int i) { return v.row(i).transpose(); }

EdgeLengthStats stats_of(std::vector<double> lengths) {
  EdgeLengthStats s;
  if (lengths.empty()) return s;
  s.count = static_cast<int>(lengths.size());
  std::sort(lengths.begin(), lengths.end());
  s.min = lengths.front();
  s.max = lengths.back();
  double sum = 0.0, sum_sq = 0.0;
  for (double l : lengths) {
    sum += l;
    sum_sq += l * l;
  }
  s.mean = sum / s.count;
  s.rms = std::sqrt(sum_sq / s.count);
  const std::size_t mid = lengths.size() / 2;
  s.median = lengths.size() % 2 ? lengths[mid] : 0.5 * (lengths[mid - 1] + lengths[mid]);
  return s;
}

/// Lengths of the distinct vertex pairs listed in `pairs` (unordered).
std::vector<double> distinct_edge_lengths(const Points3& v, std::vector<std::array<int, 2>> pairs) {
  for (auto& p : pairs)
    if (p[0] > p[1]) std::swap(p[0], p[1]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<double> lengths;
  lengths.reserve(pairs.size());
  for (const auto& p : pairs)
    if (p[0] != p[1]) lengths.push_back((v.row(p[0]) - v.row(p[1])).norm());
  return lengths;
}

}  // namespace

double signed_volume(const TriMesh& mesh) {
  double six_v = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 a = corner(mesh.vertices, mesh.faces(f, 0));
    const Vec3 b = corner(mesh.vertices, mesh.faces(f, 1));
    const Vec3 c = corner(mesh.vertices, mesh.faces(f, 2));
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6.0;
}

double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

double face_area(const TriMesh& mesh, int f) {
  return triangle_area(corner(mesh.vertices, mesh.faces(f, 0)),
                       corner(mesh.vertices, mesh.faces(f, 1)),
                       corner(mesh.vertices, mesh.faces(f, 2)));
}

VecX face_areas(const TriMesh& mesh) {
  VecX areas(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) areas[f] = face_area(mesh, f);
  return areas;
}

double surface_area(const TriMesh& mesh) { return face_areas(mesh).sum(); }

Points3 face_normals(const TriMesh& mesh) {
  Points3 normals(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 a = corner(mesh.vertices, mesh.faces(f, 0));
    const Vec3 b = corner(mesh.vertices, mesh.faces(f, 1));
    const Vec3 c = corner(mesh.vertices, mesh.faces(f, 2));
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    normals.row(f) = (len > 0.0 ? Vec3(n / len) : Vec3(Vec3::Zero())).transpose();
  }
  return normals;
}

Points3 vertex_normals(const TriMesh& mesh) {
  Points3 normals = Points3::Zero(mesh.num_vertices(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 a = corner(mesh.vertices, mesh.faces(f, 0));
    const Vec3 b = corner(mesh.vertices, mesh.faces(f, 1));
    const Vec3 c = corner(mesh.vertices, mesh.faces(f, 2));
    const Vec3 n = (b - a).cross(c - a);  // length = 2 × area
    for (int k = 0; k < 3; ++k) normals.row(mesh.faces(f, k)) += n.transpose();
  }
  for (int i = 0; i < normals.rows(); ++i) {
    const double len = normals.row(i).norm();
    if (len > 0.0) normals.row(i) /= len;
  }
  return normals;
}

EdgeLengthStats edge_length_stats(const TriMesh& mesh) {
  std::vector<std::array<int, 2>> pairs;
  pairs.reserve(3 * static_cast<std::size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int i = 0; i < 3; ++i) pairs.push_back({mesh.faces(f, i), mesh.faces(f, (i + 1) % 3)});
  return stats_of(distinct_edge_lengths(mesh.vertices, std::move(pairs)));
}

EdgeLengthStats edge_length_stats(const TetMesh& mesh) {
  std::vector<std::array<int, 2>> pairs;
  pairs.reserve(6 * static_cast<std::size_t>(mesh.num_tets()));
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) pairs.push_back({mesh.tets(t, i), mesh.tets(t, j)});
  return stats_of(distinct_edge_lengths(mesh.vertices, std::move(pairs)));
}

double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

VecX tet_volumes(const TetMesh& mesh) {
  VecX vols(mesh.num_tets());
  for (int t = 0; t < mesh.num_tets(); ++t)
    vols[t] =
        tet_volume(corner(mesh.vertices, mesh.tets(t, 0)), corner(mesh.vertices, mesh.tets(t, 1)),
                   corner(mesh.vertices, mesh.tets(t, 2)), corner(mesh.vertices, mesh.tets(t, 3)));
  return vols;
}

double total_volume(const TetMesh& mesh) { return tet_volumes(mesh).sum(); }

std::array<double, 6> tet_dihedral_angles(const Vec3& a, const Vec3& b, const Vec3& c,
                                          const Vec3& d) {
  // n_k is the unit normal of the face opposite corner k, pointing towards corner k
  // (inward), so the result does not depend on the tet's orientation. The interior dihedral angle
  // at the edge shared by faces opposite i and j is π − angle(n_i, n_j).
  const std::array<Vec3, 4> p = {a, b, c, d};
  std::array<Vec3, 4> n;
  for (int k = 0; k < 4; ++k) {
    const Vec3& q0 = p[(k + 1) % 4];
    const Vec3& q1 = p[(k + 2) % 4];
    const Vec3& q2 = p[(k + 3) % 4];
    Vec3 normal = (q1 - q0).cross(q2 - q0);
    const double len = normal.norm();
    if (len == 0.0) return {0, 0, 0, 0, 0, 0};
    normal /= len;
    if (normal.dot(p[k] - q0) < 0) normal = -normal;
    n[k] = normal;
  }
  // Edge (i, j) is shared by the faces opposite the two other corners.
  static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  std::array<double, 6> angles{};
  for (int e = 0; e < 6; ++e) {
    int others[2], m = 0;
    for (int k = 0; k < 4; ++k)
      if (k != kEdges[e][0] && k != kEdges[e][1]) others[m++] = k;
    const double cosine = std::clamp(n[others[0]].dot(n[others[1]]), -1.0, 1.0);
    angles[e] = 180.0 - std::acos(cosine) * 180.0 / std::numbers::pi;
  }
  return angles;
}

AngleRange dihedral_angle_range(const TetMesh& mesh) {
  if (mesh.num_tets() == 0) return {};
  AngleRange range{std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity()};
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const auto angles = tet_dihedral_angles(
        corner(mesh.vertices, mesh.tets(t, 0)), corner(mesh.vertices, mesh.tets(t, 1)),
        corner(mesh.vertices, mesh.tets(t, 2)), corner(mesh.vertices, mesh.tets(t, 3)));
    for (double x : angles) {
      range.min_degrees = std::min(range.min_degrees, x);
      range.max_degrees = std::max(range.max_degrees, x);
    }
  }
  return range;
}

double tet_radius_edge_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // Circumcentre relative to a: x solves 2 [u v w]^T x = [|u|², |v|², |w|²].
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double det = 2.0 * u.dot(v.cross(w));
  const double shortest =
      std::min({u.norm(), v.norm(), w.norm(), (c - b).norm(), (d - b).norm(), (d - c).norm()});
  if (det == 0.0 || shortest == 0.0) return std::numeric_limits<double>::infinity();
  const Vec3 x =
      (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) /
      det;
  return x.norm() / shortest;
}

VecX radius_edge_ratios(const TetMesh& mesh) {
  VecX r(mesh.num_tets());
  for (int t = 0; t < mesh.num_tets(); ++t)
    r[t] = tet_radius_edge_ratio(
        corner(mesh.vertices, mesh.tets(t, 0)), corner(mesh.vertices, mesh.tets(t, 1)),
        corner(mesh.vertices, mesh.tets(t, 2)), corner(mesh.vertices, mesh.tets(t, 3)));
  return r;
}

}  // namespace tightfit
