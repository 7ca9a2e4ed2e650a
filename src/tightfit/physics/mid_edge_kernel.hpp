#pragma once
/// The per-face kernel of the mid-edge shape operator (Grinspun et al. 2006, Eq. 32-33;
/// conventions in mid_edge_shape_operator.hpp), templated on the scalar S: double for
/// the operator itself (MidEdgeShapeOperator), autodiff::Scalar<N> for the exact
/// derivatives of the pressure objective. Per face f and face edge i (corner i → i+1):
///   B_i = (l_i / A_f) t_i t_iᵀ   (1/m),   θ_i the signed dihedral angle of the edge (rad),
///   Λ_f = Σ_i (θ_i/2 + s_i φ_i) B_i,
/// with l_i the edge length (m), A_f the face area (m²), t_i the unit in-plane normal of
/// the edge pointing out of the face, s_i and φ_i the edge's sign and unknown
/// (mid_edge_topology.hpp). Positions in m, world frame.
#include <array>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "tightfit/common/error.hpp"
#include "tightfit/physics/autodiff.hpp"

namespace tightfit::mid_edge {

using autodiff::Mat3T;
using autodiff::Vec3T;

/// Geometry of one triangle at its current corner positions.
template <typename S>
struct FaceFrame {
  Vec3T<S> normal;                   ///< unit, along (p1 − p0) × (p2 − p0)
  S area;                            ///< A_f (m²)
  std::array<Vec3T<S>, 3> edge_dir;  ///< unit direction of face edge i (corner i → i+1)
  std::array<Vec3T<S>, 3> out;       ///< t_i: unit in-plane normal of edge i, out of the face
  std::array<S, 3> length;           ///< l_i (m)
};

/// Frame of face `face` with corners p0, p1, p2. Throws SolverError when the face is
/// degenerate: twice its area not above 1e-12 (|p1 − p0|² + |p2 − p0|²).
template <typename S>
FaceFrame<S> face_frame(const Vec3T<S>& p0, const Vec3T<S>& p1, const Vec3T<S>& p2, int face) {
  using autodiff::value_of;
  using std::sqrt;
  FaceFrame<S> fr;
  const Vec3T<S> n = (p1 - p0).cross(p2 - p0);
  const S twice_area = sqrt(n.squaredNorm());
  const double scale = value_of((p1 - p0).squaredNorm()) + value_of((p2 - p0).squaredNorm());
  if (!(value_of(twice_area) > 1e-12 * scale))
    throw SolverError("mid-edge shape operator: face " + std::to_string(face) + " is degenerate");
  fr.normal = n / twice_area;
  fr.area = 0.5 * twice_area;
  const std::array<const Vec3T<S>*, 3> p = {&p0, &p1, &p2};
  for (int i = 0; i < 3; ++i) {
    const Vec3T<S> e = *p[(i + 1) % 3] - *p[i];
    fr.length[i] = sqrt(e.squaredNorm());
    fr.edge_dir[i] = e / fr.length[i];
    fr.out[i] = fr.edge_dir[i].cross(fr.normal);
  }
  return fr;
}

/// Signed dihedral angle θ (rad, in (−π, π]) at an edge with unit direction `edge_dir`
/// as seen from face f (its corner i → i+1), between the unit normals n_f of f and n_g
/// of the face across: positive where the surface is convex seen from the side the
/// normals point to. The same in both faces of the edge.
template <typename S>
S dihedral_angle(const Vec3T<S>& n_f, const Vec3T<S>& n_g, const Vec3T<S>& edge_dir) {
  using std::atan2;
  return atan2(n_f.cross(n_g).dot(edge_dir), n_f.dot(n_g));
}

/// The operator pieces of one face: Λ_f = Σ_i (θ_i/2 + s_i φ_i) b[i].
template <typename S>
struct FaceOperator {
  S area;                     ///< A_f (m²)
  std::array<Mat3T<S>, 3> b;  ///< B_i = (l_i / A_f) t_i t_iᵀ (3×3 symmetric, 1/m)
  std::array<S, 3> theta;     ///< θ_i (rad), 0 on a boundary edge
};

/// Sets `op`'s area and B_i from a face frame (θ untouched).
template <typename S>
void set_bending_matrices(const FaceFrame<S>& frame, FaceOperator<S>& op) {
  op.area = frame.area;
  for (int i = 0; i < 3; ++i)
    op.b[i] = (frame.length[i] / frame.area) * frame.out[i] * frame.out[i].transpose();
}

/// The pieces of a face from its frame and the dihedral angles of its three edges.
template <typename S>
FaceOperator<S> face_operator(const FaceFrame<S>& frame, const std::array<S, 3>& theta) {
  FaceOperator<S> op;
  set_bending_matrices(frame, op);
  op.theta = theta;
  return op;
}

/// The pieces of face `face` from local positions alone (the form to differentiate):
/// `p` holds the face's corners 0..2, then the vertices across its edges 0..2 (the
/// corner of the neighbouring face that is not on the edge; ignored where
/// `has_across[i]` is false, a boundary edge). Throws SolverError for a degenerate face
/// or neighbouring face.
template <typename S>
FaceOperator<S> face_operator(const std::array<Vec3T<S>, 6>& p,
                              const std::array<bool, 3>& has_across, int face) {
  using autodiff::value_of;
  using std::sqrt;
  const FaceFrame<S> fr = face_frame<S>(p[0], p[1], p[2], face);
  FaceOperator<S> op;
  set_bending_matrices(fr, op);
  for (int i = 0; i < 3; ++i) {
    if (!has_across[i]) {
      op.theta[i] = S(0.0);
      continue;
    }
    // The neighbour has the edge reversed: corners i+1, i, then the vertex across.
    const Vec3T<S>& a = p[(i + 1) % 3];
    const Vec3T<S> ng = (p[i] - a).cross(p[3 + i] - a);
    const S ng_len = sqrt(ng.squaredNorm());
    if (!(value_of(ng_len) > 0.0))
      throw SolverError("mid-edge shape operator: the face across edge " + std::to_string(i) +
                        " of face " + std::to_string(face) + " is degenerate");
    op.theta[i] = dihedral_angle<S>(fr.normal, Vec3T<S>(ng / ng_len), fr.edge_dir[i]);
  }
  return op;
}

/// Gram matrix ⟨B_i, B_j⟩ (Frobenius inner products, 3×3, 1/m²) of a face: the face's
/// term A_f tr(Λ_f²) of Eq. 33 is A_f cᵀ G c with c_i = θ_i/2 + s_i φ_i.
template <typename S>
Mat3T<S> gram(const FaceOperator<S>& op) {
  Mat3T<S> g;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      g(i, j) = op.b[i].cwiseProduct(op.b[j]).sum();
      if (j != i) g(j, i) = g(i, j);
    }
  return g;
}

/// The coefficient θ_i/2 + s_i φ_i of B_i in Λ_f; `phi` may be double or S.
template <typename S, typename T>
S coefficient(const FaceOperator<S>& op, int i, int sign, const T& phi) {
  return 0.5 * op.theta[i] + static_cast<double>(sign) * phi;
}

/// Λ_f = Σ_i (θ_i/2 + s_i φ_i) B_i (3×3 symmetric, 1/m, Λ n_f = 0) from the face's
/// pieces, the signs s_i and the unknowns φ_i (rad; double or S) of its three edges.
template <typename S, typename T>
Mat3T<S> shape_operator(const FaceOperator<S>& op, const std::array<int, 3>& sign,
                        const std::array<T, 3>& phi) {
  Mat3T<S> lambda = coefficient(op, 0, sign[0], phi[0]) * op.b[0];
  for (int i = 1; i < 3; ++i) lambda += coefficient(op, i, sign[i], phi[i]) * op.b[i];
  return lambda;
}

}  // namespace tightfit::mid_edge
