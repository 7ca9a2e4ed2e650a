#include "tightfit/physics/mid_edge_shape_operator.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "tightfit/common/error.hpp"

namespace tightfit {

MidEdgeShapeOperator::MidEdgeShapeOperator(const Triangles& faces, int num_vertices)
    : MidEdgeShapeOperator(std::make_shared<const MidEdgeTopology>(faces, num_vertices)) {}

MidEdgeShapeOperator::MidEdgeShapeOperator(std::shared_ptr<const MidEdgeTopology> topology)
    : topology_(std::move(topology)) {
  if (!topology_) throw std::invalid_argument("MidEdgeShapeOperator: null topology");
}

std::vector<Mat3> MidEdgeShapeOperator::compute(const Eigen::Ref<const Points3>& vertices) {
  const MidEdgeTopology& topo = *topology_;
  if (vertices.rows() != topo.num_vertices())
    throw std::invalid_argument("MidEdgeShapeOperator: expected " +
                                std::to_string(topo.num_vertices()) + " vertices, got " +
                                std::to_string(vertices.rows()));
  const Triangles& faces = topo.faces();
  const int m = topo.num_faces();
  std::vector<mid_edge::FaceFrame<double>> frames(m);
  for (int f = 0; f < m; ++f)
    frames[f] = mid_edge::face_frame<double>(vertices.row(faces(f, 0)).transpose(),
                                             vertices.row(faces(f, 1)).transpose(),
                                             vertices.row(faces(f, 2)).transpose(), f);

  // Signed dihedral angle per edge, positive where convex; 0 on boundary edges.
  const int ne = topo.num_edges();
  const std::vector<int>& first = topo.edge_face_edges();
  VecX theta = VecX::Zero(ne);
  for (int k = 0; k < ne; ++k) {
    const int h = first[k];
    const int g = topo.across(h / 3, h % 3);
    if (g < 0) continue;
    const mid_edge::FaceFrame<double>& a = frames[h / 3];
    theta[k] = mid_edge::dihedral_angle<double>(a.normal, frames[g / 3].normal, a.edge_dir[h % 3]);
  }

  // Per face: Λ_f = Σ_i c_i B_i with c_i = θ_i/2 + s_i φ_i, and ψ_f = A_f tr(Λ_f²) =
  // A_f cᵀ G_f c (G_f the Gram matrix of the B_i): normal equations
  // K φ = −Σ_f A_f s ⊙ (G_f θ/2), K_ij = Σ_f A_f s_i s_j (G_f)_ij.
  ops_.resize(m);
  std::vector<Triplet> triplets;
  triplets.reserve(9 * static_cast<std::size_t>(m));
  VecX rhs = VecX::Zero(ne);
  for (int f = 0; f < m; ++f) {
    const std::array<int, 3> e = topo.edges(f);
    const std::array<int, 3> s = topo.signs(f);
    ops_[f] = mid_edge::face_operator<double>(frames[f], {theta[e[0]], theta[e[1]], theta[e[2]]});
    const mid_edge::FaceOperator<double>& op = ops_[f];
    const Mat3 g = mid_edge::gram(op);
    for (int i = 0; i < 3; ++i) {
      double r = 0.0;
      for (int j = 0; j < 3; ++j) {
        triplets.emplace_back(e[i], e[j], op.area * s[i] * s[j] * g(i, j));
        r += 0.5 * op.theta[j] * g(i, j);
      }
      rhs[e[i]] -= op.area * s[i] * r;
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
    const std::array<int, 3> e = topo.edges(f);
    const std::array<double, 3> phi = {phi_[e[0]], phi_[e[1]], phi_[e[2]]};
    const Mat3 l = mid_edge::shape_operator(ops_[f], topo.signs(f), phi);
    result[f] = 0.5 * (l + l.transpose());
  }
  return result;
}

VecX MidEdgeShapeOperator::solve_with_system_matrix(const VecX& rhs) const {
  if (rhs.size() != num_edges())
    throw std::invalid_argument("MidEdgeShapeOperator: right-hand side has " +
                                std::to_string(rhs.size()) + " entries for " +
                                std::to_string(num_edges()) + " edges");
  if (num_edges() == 0) return VecX();
  if (phi_.size() != num_edges())
    throw std::logic_error("MidEdgeShapeOperator: solve_with_system_matrix before compute");
  return solver_.solve(rhs);
}

std::vector<Mat3> mid_edge_shape_operators(const Points3& vertices, const Triangles& faces) {
  MidEdgeShapeOperator op(faces, static_cast<int>(vertices.rows()));
  return op.compute(vertices);
}

}  // namespace tightfit
