#pragma once
/// Discrete shape operator of Grinspun, Gingold, Reisman and Zorin 2006 from mid-edge
/// normals (paper Eq. 32-33), per triangle of a 3D triangle mesh.
///
///   Λ_f = Σ_{i=0..2} φ̃_i (l_i / A_f) t_i t_iᵀ,
/// with l_i the length of face edge i (corner i → i+1), t_i the unit in-plane normal of
/// that edge pointing out of the face, A_f the face area and φ̃_i the angle by which the
/// mid-edge normal of edge i is tilted from the face normal towards t_i. (Eq. 32 writes
/// the same with t_i of length l_i.) On an interior edge shared by faces f, g with signed
/// dihedral angle θ (positive where the surface is convex seen from the side the normals
/// point to), φ̃ = θ/2 + s φ in f and θ/2 - s φ in g (s = +1 in the edge's first face),
/// and the per-edge unknowns φ minimize Σ_f A_f tr(Λ_f²) (Eq. 33): one sparse symmetric
/// positive definite system, solved with CHOLMOD (the symbolic analysis is reused while
/// the topology stays the same).
///
/// Sign convention: Λ is the derivative of the unit normal, so with outward normals
/// (faces counter-clockwise seen from outside) a sphere of radius R has Λ = I/R and a
/// cylinder has eigenvalues 1/R (around) and 0 (along the axis).
///
/// Boundary edges (one face) have no dihedral angle: θ = 0 and their tilt φ̃ = φ is a
/// free unknown of the same minimization (the natural boundary condition of Eq. 33).
/// The minimizer makes the normal curvature across the boundary edge vanish in the
/// boundary face (t_iᵀ Λ_f t_i = 0). This is exact where the surface does not curve across
/// the boundary (the end rings of a sleeve: error of the interior, 4e-4 on a 64-segment
/// cylinder). Where it does curve across the boundary (a cylinder cut along its axis) the
/// curvature across the boundary is lost in the boundary faces and the error decays about
/// tenfold per ring of faces inward (measured: 100 %, 10 %, 1 %, then the interior error).
/// (A closure that extrapolates the face's own operator onto its boundary edges was tried
/// and rejected: it pollutes the whole solution by several percent on irregular meshes.)
#include <memory>
#include <vector>

#include "tightfit/common/sparse_cholesky.hpp"
#include "tightfit/common/types.hpp"
#include "tightfit/physics/mid_edge_kernel.hpp"
#include "tightfit/physics/mid_edge_topology.hpp"

namespace tightfit {

/// The per-face pieces come from mid_edge_kernel.hpp and the edge numbering and signs
/// from mid_edge_topology.hpp (both shared with the pressure objective).
class MidEdgeShapeOperator {
 public:
  /// `faces` m×3 indices in [0, num_vertices), consistently oriented. Throws InputError
  /// for out-of-range indices, edges with more than two faces and interior edges whose
  /// faces disagree on orientation.
  MidEdgeShapeOperator(const Triangles& faces, int num_vertices);
  /// On a topology built once and shared (not null).
  explicit MidEdgeShapeOperator(std::shared_ptr<const MidEdgeTopology> topology);

  /// Λ per face (3×3 symmetric, world frame, 1/m; Λ n_f = 0) at `vertices` (n×3, m).
  /// Throws SolverError if a face is degenerate (zero area) or the solve fails.
  std::vector<Mat3> compute(const Eigen::Ref<const Points3>& vertices);

  /// The per-face pieces (area, B_i, θ_i) of the last compute(), one per face.
  const std::vector<mid_edge::FaceOperator<double>>& face_operators() const { return ops_; }
  /// The edge unknowns φ (one per edge, rad) of the last compute(), in the order of
  /// edge_face_edges().
  const VecX& edge_variables() const { return phi_; }
  /// Solves K μ = rhs (one entry per edge unknown) with the symmetric positive definite
  /// matrix K of the φ system of the last compute() (K φ = r, r from the dihedral
  /// angles): the adjoint solve for derivatives through φ. Requires a compute().
  VecX solve_with_system_matrix(const VecX& rhs) const;
  /// Per edge unknown, one face edge (3·face + i) of that edge (its first face).
  const std::vector<int>& edge_face_edges() const { return topology_->edge_face_edges(); }
  int num_edges() const { return topology_->num_edges(); }
  const MidEdgeTopology& topology() const { return *topology_; }

 private:
  std::shared_ptr<const MidEdgeTopology> topology_;
  std::vector<mid_edge::FaceOperator<double>> ops_;
  SparseCholesky solver_;
  VecX phi_;
};

/// Convenience: Λ per face of the mesh (vertices n×3, faces m×3).
std::vector<Mat3> mid_edge_shape_operators(const Points3& vertices, const Triangles& faces);

}  // namespace tightfit
