#include "tightfit/garment/flatten.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/common/sparse_cholesky.hpp"

namespace tightfit {
namespace {

/// A triangle in its own plane: corner 0 at the origin, corner 1 on the x axis.
struct LocalTriangle {
  std::array<Vec2, 3> x;
  std::array<double, 3> half_cot;  // ½ cot of the angle at corner k (weight of edge k+1,k+2)
  double area = 0.0;
};

LocalTriangle local_triangle(const TriMesh& m, int f) {
  const Vec3 p0 = m.vertices.row(m.faces(f, 0)), p1 = m.vertices.row(m.faces(f, 1)),
             p2 = m.vertices.row(m.faces(f, 2));
  LocalTriangle t;
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const double l1 = e1.norm();
  const Vec3 ex = l1 > 0 ? Vec3(e1 / l1) : Vec3::UnitX();
  t.x[0] = Vec2::Zero();
  t.x[1] = Vec2(l1, 0.0);
  t.x[2] = Vec2(e2.dot(ex), e2.cross(ex).norm());
  t.area = 0.5 * l1 * t.x[2].y();
  for (int k = 0; k < 3; ++k) {
    const Vec2 a = t.x[(k + 1) % 3] - t.x[k], b = t.x[(k + 2) % 3] - t.x[k];
    const double cross = a.x() * b.y() - a.y() * b.x();
    const double cot = cross > 1e-300 ? a.dot(b) / cross : 1e4;
    t.half_cot[k] = 0.5 * std::clamp(cot, -1e4, 1e4);
  }
  return t;
}

double angle(const Vec2& a, const Vec2& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}
double angle3(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

/// Cotangent Laplacian (n×n, positive semi-definite), full symmetric storage.
SparseMatrix cot_laplacian(const std::vector<std::array<int, 3>>& faces,
                           const std::vector<LocalTriangle>& tris, int n) {
  std::vector<Triplet> trip;
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = faces[f][(k + 1) % 3], j = faces[f][(k + 2) % 3];
      const double w = tris[f].half_cot[k];
      trip.emplace_back(i, i, w);
      trip.emplace_back(j, j, w);
      trip.emplace_back(i, j, -w);
      trip.emplace_back(j, i, -w);
    }
  SparseMatrix L(n, n);
  L.setFromTriplets(trip.begin(), trip.end());
  return L;
}

/// Minimizes ½zᵀMz with z[fixed] = z0[fixed]: solves M_ff z_f = −M_fp z_p.
VecX solve_with_fixed(const SparseMatrix& M, const std::vector<char>& fixed, const VecX& z0) {
  const int n = static_cast<int>(M.rows());
  std::vector<int> id(n, -1);
  int nf = 0;
  for (int i = 0; i < n; ++i)
    if (!fixed[i]) id[i] = nf++;
  VecX rhs = VecX::Zero(nf);
  std::vector<Triplet> trip;
  for (int c = 0; c < n; ++c)
    for (SparseMatrix::InnerIterator it(M, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      if (id[r] < 0) continue;
      if (id[c] >= 0) {
        trip.emplace_back(id[r], id[c], it.value());
      } else {
        rhs[id[r]] -= it.value() * z0[c];
      }
    }
  SparseMatrix Mff(nf, nf);
  Mff.setFromTriplets(trip.begin(), trip.end());
  SparseCholesky chol;
  if (!chol.factorize(Mff))
    throw SolverError(
        "flattening: the conformal system is not positive definite (degenerate triangles?)");
  const VecX zf = chol.solve(rhs);
  VecX z = z0;
  for (int i = 0; i < n; ++i)
    if (id[i] >= 0) z[i] = zf[id[i]];
  return z;
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  auto orient = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
  };
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  return ((o1 > 0) != (o2 > 0)) && ((o3 > 0) != (o4 > 0)) && o1 != 0 && o2 != 0 && o3 != 0 &&
         o4 != 0;
}

}  // namespace

DistortionReport measure_distortion(const TriMesh& mesh, const Points2& uv) {
  DistortionReport r;
  double weight = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const LocalTriangle t = local_triangle(mesh, f);
    const Vec2 u0 = uv.row(mesh.faces(f, 0)), u1 = uv.row(mesh.faces(f, 1)),
               u2 = uv.row(mesh.faces(f, 2));
    Mat2 U, X;
    U << u1 - u0, u2 - u0;
    X << t.x[1] - t.x[0], t.x[2] - t.x[0];
    const double a2 = signed_area(u0, u1, u2);
    r.area_3d += t.area;
    r.area_2d += a2;
    if (a2 <= 0.0) ++r.flipped;
    if (t.area <= 0.0) continue;
    const Mat2 J = U * X.inverse();
    Eigen::JacobiSVD<Mat2> svd(J);
    const double s1 = svd.singularValues()[0], s2 = svd.singularValues()[1];
    const double ad = std::abs(J.determinant() - 1.0);
    r.mean_area_distortion += t.area * ad;
    r.max_area_distortion = std::max(r.max_area_distortion, ad);
    r.mean_stretch += t.area * (std::max(s1, s2 > 0 ? 1.0 / s2 : 1e300) - 1.0);
    const std::array<Vec2, 3> u{u0, u1, u2};
    const std::array<Vec3, 3> p{mesh.vertices.row(mesh.faces(f, 0)).transpose(),
                                mesh.vertices.row(mesh.faces(f, 1)).transpose(),
                                mesh.vertices.row(mesh.faces(f, 2)).transpose()};
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double a3 = angle3(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
      const double a2d = std::abs(angle(u[(k + 1) % 3] - u[k], u[(k + 2) % 3] - u[k]));
      const double e = std::abs(a2d - a3) * 180.0 / std::numbers::pi;
      sum += e;
      r.max_angle_error_deg = std::max(r.max_angle_error_deg, e);
    }
    r.mean_angle_error_deg += t.area * sum / 3.0;
    weight += t.area;
  }
  if (weight > 0) {
    r.mean_area_distortion /= weight;
    r.mean_angle_error_deg /= weight;
    r.mean_stretch /= weight;
  }
  r.area_error = r.area_3d > 0 ? std::abs(r.area_2d - r.area_3d) / r.area_3d : 0.0;
  return r;
}

namespace {

std::string format_point(const Eigen::Ref<const Eigen::RowVector3d>& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.4g, %.4g, %.4g) m", p.x(), p.y(), p.z());
  return text;
}

/// Signed area of face `f` in the map.
double face_signed_area(const std::array<int, 3>& f, const Points2& uv) {
  return signed_area(uv.row(f[0]), uv.row(f[1]), uv.row(f[2]));
}

/// Total signed area of the map.
double total_signed_area(const std::vector<std::array<int, 3>>& faces, const Points2& uv) {
  double sum = 0.0;
  for (const auto& f : faces) sum += face_signed_area(f, uv);
  return sum;
}

/// Triangles whose orientation in the map is not `orientation` (±1).
int count_folds(const std::vector<std::array<int, 3>>& faces, const Points2& uv,
                double orientation) {
  int folds = 0;
  for (const auto& f : faces) folds += orientation * face_signed_area(f, uv) <= 0.0 ? 1 : 0;
  return folds;
}

std::vector<std::pair<int, int>> loop_edges(const std::vector<std::vector<int>>& loops) {
  std::vector<std::pair<int, int>> edges;
  for (const auto& loop : loops) {
    const size_t n = loop.size();
    for (size_t k = 0; k < n; ++k) edges.emplace_back(loop[k], loop[(k + 1) % n]);
  }
  return edges;
}

}  // namespace

Flattening flatten_panel(const TriMesh& mesh, const std::vector<std::vector<int>>& loops,
                         const FlattenOptions& options) {
  const int n = mesh.num_vertices();
  const int nf = mesh.num_faces();
  if (loops.empty() || loops[0].size() < 3)
    throw std::invalid_argument("flatten_panel: boundary loop too short");
  for (const auto& loop : loops)
    if (loop.size() < 3) throw std::invalid_argument("flatten_panel: hole loop too short");
  const std::vector<int>& boundary = loops[0];
  const std::vector<std::pair<int, int>> edges = loop_edges(loops);
  std::vector<std::array<int, 3>> faces(nf);
  std::vector<LocalTriangle> tris(nf);
  for (int f = 0; f < nf; ++f) {
    faces[f] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
    tris[f] = local_triangle(mesh, f);
  }
  const SparseMatrix L = cot_laplacian(faces, tris, n);

  // LSCM: E = ½uᵀLu + ½vᵀLv − area(u, v), area = ½ Σ_boundary (u_i v_j − u_j v_i).
  std::vector<Triplet> trip;
  for (int c = 0; c < n; ++c)
    for (SparseMatrix::InnerIterator it(L, c); it; ++it) {
      trip.emplace_back(it.row(), c, it.value());
      trip.emplace_back(n + it.row(), n + c, it.value());
    }
  const int nb = static_cast<int>(edges.size());
  for (const auto& [i, j] : edges) {
    // −½ uᵀ K v with K_ij = 1, K_ji = −1, written symmetrically as [[0, −K/2], [K/2, 0]].
    trip.emplace_back(i, n + j, -0.5);
    trip.emplace_back(j, n + i, 0.5);
    trip.emplace_back(n + j, i, -0.5);
    trip.emplace_back(n + i, j, 0.5);
  }
  SparseMatrix M(2 * n, 2 * n);
  M.setFromTriplets(trip.begin(), trip.end());
  // Pins: the two boundary vertices farthest apart (two sweeps).
  auto farthest = [&](int from) {
    int best = boundary[0];
    double d = -1;
    for (int v : boundary) {
      const double dv = (mesh.vertices.row(v) - mesh.vertices.row(from)).squaredNorm();
      if (dv > d) {
        d = dv;
        best = v;
      }
    }
    return best;
  };
  const int p0 = farthest(boundary[0]);
  const int p1 = farthest(p0);
  VecX z0 = VecX::Zero(2 * n);
  z0[p1] = (mesh.vertices.row(p1) - mesh.vertices.row(p0)).norm();
  std::vector<char> fixed(2 * n, 0);
  fixed[p0] = fixed[n + p0] = fixed[p1] = fixed[n + p1] = 1;
  const VecX z = solve_with_fixed(M, fixed, z0);

  Flattening out;
  out.uv.resize(n, 2);
  out.uv.col(0) = z.head(n);
  out.uv.col(1) = z.tail(n);

  if (options.max_iterations > 0) {
    // ARAP: E = Σ_t Σ_edges ½cot ‖(u_i − u_j) − R_t (x_i − x_j)‖², vertex p0 fixed.
    // The global step solves L u = b for both coordinates with one factorization.
    std::vector<int> id(n, -1);
    int m = 0;
    for (int i = 0; i < n; ++i)
      if (i != p0) id[i] = m++;
    // Boundary term: w Σ_e ‖(u_i − u_j) − ℓ_e d_e‖², ℓ_e the 3D length, d_e a unit direction.
    const double w = options.boundary_weight;
    std::vector<double> boundary_length(nb);
    std::vector<Triplet> lt;
    for (int k = 0; k < nb; ++k) {
      const auto [i, j] = edges[k];
      boundary_length[k] = (mesh.vertices.row(i) - mesh.vertices.row(j)).norm();
      lt.emplace_back(i, i, w);
      lt.emplace_back(j, j, w);
      lt.emplace_back(i, j, -w);
      lt.emplace_back(j, i, -w);
    }
    SparseMatrix A(n, n);
    A.setFromTriplets(lt.begin(), lt.end());
    A += L;
    std::vector<Triplet> lff;
    for (int c = 0; c < n; ++c)
      for (SparseMatrix::InnerIterator e(A, c); e; ++e)
        if (id[e.row()] >= 0 && id[c] >= 0) lff.emplace_back(id[e.row()], id[c], e.value());
    SparseMatrix Lff(m, m);
    Lff.setFromTriplets(lff.begin(), lff.end());
    SparseCholesky chol;
    if (!chol.factorize(Lff))
      throw SolverError(
          "flattening: the ARAP system is not positive definite (degenerate triangles?)");
    std::vector<Mat2> R(nf);
    double previous = std::numeric_limits<double>::infinity();
    const double orientation = total_signed_area(faces, out.uv) < 0.0 ? -1.0 : 1.0;
    int folds_before = count_folds(faces, out.uv, orientation);
    for (int it = 0; it < options.max_iterations; ++it) {
      // Local step: the rotation closest to each triangle's map (2×2 polar decomposition).
      double energy = 0.0;
      for (int f = 0; f < nf; ++f) {
        Mat2 S = Mat2::Zero();
        for (int k = 0; k < 3; ++k) {
          const int a = (k + 1) % 3, b = (k + 2) % 3;
          const Vec2 du = out.uv.row(faces[f][a]) - out.uv.row(faces[f][b]);
          S += tris[f].half_cot[k] * du * (tris[f].x[a] - tris[f].x[b]).transpose();
        }
        const double theta = std::atan2(S(1, 0) - S(0, 1), S(0, 0) + S(1, 1));
        R[f] << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
        for (int k = 0; k < 3; ++k) {
          const int a = (k + 1) % 3, b = (k + 2) % 3;
          const Vec2 du = out.uv.row(faces[f][a]) - out.uv.row(faces[f][b]);
          energy += tris[f].half_cot[k] * (du - R[f] * (tris[f].x[a] - tris[f].x[b])).squaredNorm();
        }
      }
      std::vector<Vec2> target(nb);
      for (int k = 0; k < nb; ++k) {
        const Vec2 du = out.uv.row(edges[k].first) - out.uv.row(edges[k].second);
        const double len = du.norm();
        target[k] = len > 0 ? Vec2(boundary_length[k] / len * du) : Vec2::Zero();
        energy += w * (du - target[k]).squaredNorm();
      }
      if (it > 0 && previous - energy <= options.tolerance * previous) break;
      previous = energy;
      // Global step.
      MatX rhs = MatX::Zero(m, 2);
      for (int f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
          const int a = faces[f][(k + 1) % 3], b = faces[f][(k + 2) % 3];
          const Vec2 r =
              tris[f].half_cot[k] * (R[f] * (tris[f].x[(k + 1) % 3] - tris[f].x[(k + 2) % 3]));
          if (id[a] >= 0) rhs.row(id[a]) += r.transpose();
          if (id[b] >= 0) rhs.row(id[b]) -= r.transpose();
        }
      for (int k = 0; k < nb; ++k) {
        const auto [a, b] = edges[k];
        if (id[a] >= 0) rhs.row(id[a]) += w * target[k].transpose();
        if (id[b] >= 0) rhs.row(id[b]) -= w * target[k].transpose();
      }
      for (SparseMatrix::InnerIterator e(A, p0); e; ++e)
        if (id[e.row()] >= 0) rhs.row(id[e.row()]) -= e.value() * out.uv.row(p0);
      const MatX u = chol.solve_columns(rhs);
      const Points2 before = out.uv;
      for (int i = 0; i < n; ++i)
        if (id[i] >= 0) out.uv.row(i) = u.row(id[i]);
      // The boundary-length pull can fold tiny triangles at sharp corners of strongly
      // curved panels: a step that folds more triangles than the iterate before is
      // shortened (halved up to 20 times) until it does not; when no length works,
      // the iterations stop at the last iterate.
      int folds = count_folds(faces, out.uv, orientation);
      if (folds > folds_before) {
        const Points2 full = out.uv;
        double alpha = 1.0;
        for (int halving = 0; halving < 20 && folds > folds_before; ++halving) {
          alpha *= 0.5;
          out.uv = before + alpha * (full - before);
          folds = count_folds(faces, out.uv, orientation);
        }
        if (folds > folds_before) {
          out.uv = before;
          break;
        }
      }
      folds_before = folds;
      out.iterations = it + 1;
    }
  }
  // Orientation: the maps preserve it; guard against a mirrored result anyway.
  if (total_signed_area(faces, out.uv) < 0) out.uv.col(0) = -out.uv.col(0);
  out.report = measure_distortion(mesh, out.uv);
  return out;
}

std::string find_overlap(const TriMesh& mesh, const std::vector<int>& boundary, const Points2& uv) {
  return find_overlap(mesh, std::vector<std::vector<int>>{boundary}, uv);
}

std::string find_overlap(const TriMesh& mesh, const std::vector<std::vector<int>>& loops,
                         const Points2& uv) {
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec2 a = uv.row(mesh.faces(f, 0)), b = uv.row(mesh.faces(f, 1)),
               c = uv.row(mesh.faces(f, 2));
    if ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() <= 0.0)
      return "a triangle is folded over near " + format_point(mesh.vertices.row(mesh.faces(f, 0)));
  }
  const std::vector<std::pair<int, int>> edges = loop_edges(loops);
  const size_t n = edges.size();
  std::vector<Eigen::AlignedBox2d> box(n);
  for (size_t i = 0; i < n; ++i) {
    box[i].extend(uv.row(edges[i].first).transpose());
    box[i].extend(uv.row(edges[i].second).transpose());
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const auto [a, b] = edges[i];
      const auto [c, d] = edges[j];
      if (a == c || a == d || b == c || b == d) continue;  // neighbours along a loop
      if (!box[i].intersects(box[j])) continue;
      if (segments_cross(uv.row(a), uv.row(b), uv.row(c), uv.row(d)))
        return "its boundary crosses itself: the edges near " + format_point(mesh.vertices.row(a)) +
               " and " + format_point(mesh.vertices.row(c)) + " cross";
    }
  // Every hole must lie inside the outer loop (folded-free maps of an annulus can put
  // the "outer" loop inside the hole instead: a band around the body, not an opening).
  for (size_t h = 1; h < loops.size(); ++h) {
    const auto& outer = loops[0];
    const auto corner = [&](size_t i) -> Vec2 { return uv.row(outer[i]); };
    if (!inside_polygon(outer.size(), corner, uv.row(loops[h][0])))
      return "an opening lies outside its outer boundary (a band around the body?)";
  }
  return "";
}

}  // namespace tightfit
