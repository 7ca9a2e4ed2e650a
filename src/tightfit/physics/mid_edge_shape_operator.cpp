#include "tightfit/physics/mid_edge_shape_operator.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "tightfit/common/error.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit {
namespace {

const std::string kMidEdgeSource = "garment mesh (shape operator)";

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9x3 = Eigen::Matrix<double, 9, 3>;

/// Geometry of one face at the current positions.
struct FaceFrame {
  Vec3 normal;  // unit
  double area = 0.0;
  std::array<Vec3, 3> edge_dir;  // unit direction of face edge i (corner i → i+1)
  std::array<Vec3, 3> out;       // unit in-plane normal of edge i, pointing out of the face
  std::array<double, 3> length;
};

FaceFrame face_frame(const Points3& v, const Triangles& faces, int f) {
  FaceFrame fr;
  const std::array<Vec3, 3> p = {v.row(faces(f, 0)).transpose(), v.row(faces(f, 1)).transpose(),
                                 v.row(faces(f, 2)).transpose()};
  const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);
  const double twice_area = n.norm();
  const double scale = (p[1] - p[0]).squaredNorm() + (p[2] - p[0]).squaredNorm();
  if (!(twice_area > 1e-12 * scale))
    throw SolverError("mid-edge shape operator: face " + std::to_string(f) + " is degenerate");
  fr.normal = n / twice_area;
  fr.area = 0.5 * twice_area;
  for (int i = 0; i < 3; ++i) {
    const Vec3 e = p[(i + 1) % 3] - p[i];
    fr.length[i] = e.norm();
    fr.edge_dir[i] = e / fr.length[i];
    fr.out[i] = fr.edge_dir[i].cross(fr.normal);
  }
  return fr;
}

}  // namespace

MidEdgeShapeOperator::MidEdgeShapeOperator(const Triangles& faces, int num_vertices)
    : faces_(faces), num_vertices_(num_vertices) {
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= num_vertices)
        throw InputError(kMidEdgeSource, "face " + std::to_string(f) + " has vertex index " +
                                             std::to_string(faces(f, k)) + " outside [0, " +
                                             std::to_string(num_vertices) + ")");
    if (faces(f, 0) == faces(f, 1) || faces(f, 1) == faces(f, 2) || faces(f, 2) == faces(f, 0))
      throw InputError(kMidEdgeSource, "face " + std::to_string(f) + " repeats a vertex");
  }
  const SurfaceTopology topo(faces, num_vertices);
  if (!topo.non_manifold_edges().empty())
    throw InputError(kMidEdgeSource, "has " + std::to_string(topo.non_manifold_edges().size()) +
                                         " edges with more than two faces");
  if (!topo.inconsistently_oriented_edges().empty())
    throw InputError(kMidEdgeSource,
                     "faces are not consistently oriented at " +
                         std::to_string(topo.inconsistently_oriented_edges().size()) + " edges");
  const int m = topo.num_faces();
  unknown_.assign(3 * m, -1);
  sign_.assign(3 * m, 1);
  opposite_.assign(3 * m, -1);
  for (int f = 0; f < m; ++f)
    for (int i = 0; i < 3; ++i) {
      if (unknown_[3 * f + i] >= 0) continue;  // already set from the other face
      const int k = static_cast<int>(edges_.size());
      edges_.push_back(3 * f + i);
      unknown_[3 * f + i] = k;
      if (topo.edge_valence(topo.face_edge(f, i)) != 2) continue;  // boundary edge
      const auto across = topo.across(f, i);
      const int h = 3 * across.face + across.edge_in_face;
      unknown_[h] = k;
      sign_[h] = -1;
      opposite_[3 * f + i] = h;
      opposite_[h] = 3 * f + i;
    }
}

std::vector<Mat3> MidEdgeShapeOperator::compute(const Points3& vertices) {
  if (vertices.rows() != num_vertices_)
    throw std::invalid_argument("MidEdgeShapeOperator: expected " + std::to_string(num_vertices_) +
                                " vertices, got " + std::to_string(vertices.rows()));
  const int m = static_cast<int>(faces_.rows());
  std::vector<FaceFrame> frames(m);
  for (int f = 0; f < m; ++f) frames[f] = face_frame(vertices, faces_, f);

  // Signed dihedral angle per edge, positive where convex; 0 on boundary edges.
  const int ne = num_edges();
  VecX theta = VecX::Zero(ne);
  for (int k = 0; k < ne; ++k) {
    const int h = edges_[k];
    if (opposite_[h] < 0) continue;
    const FaceFrame& a = frames[h / 3];
    const Vec3& nb = frames[opposite_[h] / 3].normal;
    theta[k] = std::atan2(a.normal.cross(nb).dot(a.edge_dir[h % 3]), a.normal.dot(nb));
  }

  // Per face: vec(Λ_f) = lambda0_f + G_f φ_f with φ_f the unknowns of its three edges,
  // lambda0_f = Σ_i (θ_i/2) vec(B_i), G_f = [s_i vec(B_i)], B_i = (l_i/A) t_i t_iᵀ.
  std::vector<Vec9> lambda0(m);
  std::vector<Mat9x3> gmat(m);
  std::vector<Triplet> triplets;
  triplets.reserve(9 * static_cast<std::size_t>(m));
  VecX rhs = VecX::Zero(ne);
  for (int f = 0; f < m; ++f) {
    const FaceFrame& fr = frames[f];
    lambda0[f].setZero();
    for (int i = 0; i < 3; ++i) {
      const Mat3 b = fr.length[i] / fr.area * fr.out[i] * fr.out[i].transpose();
      const Vec9 vb = Eigen::Map<const Vec9>(b.data());
      gmat[f].col(i) = sign_[3 * f + i] * vb;
      lambda0[f] += 0.5 * theta[unknown_[3 * f + i]] * vb;
    }
    // ψ_f = A_f |lambda0 + G φ|²: normal equations K φ = -Σ_f A_f Gᵀ lambda0.
    const Mat3 k = fr.area * gmat[f].transpose() * gmat[f];
    const Vec3 b = -fr.area * gmat[f].transpose() * lambda0[f];
    for (int i = 0; i < 3; ++i) {
      rhs[unknown_[3 * f + i]] += b[i];
      for (int j = 0; j < 3; ++j)
        triplets.emplace_back(unknown_[3 * f + i], unknown_[3 * f + j], k(i, j));
    }
  }

  phi_ = VecX::Zero(ne);
  if (ne > 0) {
    SparseMatrix kmat(ne, ne);
    kmat.setFromTriplets(triplets.begin(), triplets.end());
    if (!solver_.factorize(kmat))
      throw SolverError("mid-edge shape operator: system is not positive definite");
    phi_ = solver_.solve(rhs);
  }

  std::vector<Mat3> result(m);
  for (int f = 0; f < m; ++f) {
    Vec9 v = lambda0[f];
    for (int i = 0; i < 3; ++i) v += gmat[f].col(i) * phi_[unknown_[3 * f + i]];
    const Mat3 l = Eigen::Map<const Mat3>(v.data());
    result[f] = 0.5 * (l + l.transpose());
  }
  return result;
}

std::vector<Mat3> mid_edge_shape_operators(const Points3& vertices, const Triangles& faces) {
  MidEdgeShapeOperator op(faces, static_cast<int>(vertices.rows()));
  return op.compute(vertices);
}

}  // namespace tightfit
