#pragma once
/// Pattern parametrization (paper Sec. 4): the design parameters p are the 2D positions
/// (m) of the pattern boundary vertices; every rest position follows linearly,
/// Xbar = W p, with W the biharmonic coordinates of Wang, Jacobson, Barbič and Kavan 2015
/// ("Linear subspace design for real-time shape deformation").
///
/// Per piece, the interior values f_I minimize the discrete ∫|Δf|² with the boundary
/// values f_B fixed:
///   E(f) = fᵀ Q f,   Q = L̃ᵀ M⁻¹ L̃,
///   L̃ = −K + N,  K the cotangent stiffness matrix (K_ij = Σ_t A_t ∇φ_i·∇φ_j),
///                N the boundary term ∫_∂Ω φ_i ∂f/∂n with ∂f/∂n taken from the gradient
///                of f in the triangle of each mesh-boundary edge,
///   M  the lumped (barycentric) mass, M_ii = Σ_{t∋i} A_t/3 (m²).
/// L̃ f is the weak Laplacian ∫ φ_i Δf, which vanishes EXACTLY on affine f at every
/// vertex, boundary ones included (divergence theorem). Hence affine f has zero energy
/// and the coordinates reproduce affine maps exactly (Wang et al.'s linear precision;
/// the plain L M⁻¹ L with the cotangent Laplacian does not). The optimality condition
/// Q_II f_I = −Q_IB f_B gives, per piece, W = [I ; −Q_II⁻¹ Q_IB] (rows reordered to the
/// piece's vertex order), one Cholesky factorization of Q_II (SparseCholesky) solved for
/// all boundary columns at once. W is dense (n × n_b) and rebuilt after remeshing by
/// constructing a new object.
///
/// Parameter layout: p stacks, piece after piece, the vertices of each piece's boundary
/// loops (PatternPiece::boundary_vertices(): the outer loop, then each hole's, in loop
/// order) as (x, y) pairs: p has 2·Σ n_b entries,
/// parameter point j is global pattern vertex parameter_vertices()[j]. Xbar is the
/// stacked rest positions of all pattern vertices (n_p×2, global numbering piece after
/// piece as in Garment::piece_offset).
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/garment/pattern.hpp"

namespace tightfit {

/// Biharmonic coordinates of one meshed piece.
class PieceBiharmonicCoordinates {
 public:
  /// Builds W from the piece's current rest mesh. Throws InputError (source "pattern
  /// piece NAME") for bad indices, a boundary loop with repeated or out-of-range
  /// vertices, fewer than 3 boundary vertices, a vertex in no triangle, or a degenerate
  /// or clockwise (inverted) triangle; SolverError when Q_II is not positive definite.
  /// The vertices of every boundary loop (outer and holes) are the handles; every
  /// other vertex is interior.
  explicit PieceBiharmonicCoordinates(const PatternPiece& piece);

  int num_vertices() const { return static_cast<int>(weights_.rows()); }
  int num_boundary() const { return static_cast<int>(weights_.cols()); }
  /// The boundary vertices (piece vertex indices, PatternPiece::boundary_vertices()),
  /// i.e. the columns of W.
  const std::vector<int>& boundary() const { return boundary_; }
  /// W (n × n_b, dimensionless): rest = W · boundary positions. Boundary rows are unit
  /// rows; every row sums to 1.
  const MatX& weights() const { return weights_; }

  /// Rest positions of all piece vertices (n×2, m) from boundary positions (n_b×2, m).
  Points2 apply(const Points2& boundary_positions) const;
  /// Wᵀ g: pulls a per-vertex gradient (n×2) back to the boundary vertices (n_b×2).
  Points2 apply_transpose(const Points2& per_vertex) const;

 private:
  std::vector<int> boundary_;
  MatX weights_;
};

/// Biharmonic coordinates of a whole pattern: the map p → Xbar.
class BiharmonicCoordinates {
 public:
  /// Builds every piece's coordinates from the pattern's current rest meshes (see
  /// PieceBiharmonicCoordinates for the errors).
  explicit BiharmonicCoordinates(const Pattern& pattern);
  /// The same after remeshing some pieces: piece k with reuse[k] keeps the coordinates
  /// (and so the factorization work) of `previous`.piece(k), the others are built from
  /// their new meshes. Throws std::invalid_argument when a reused piece's vertex count
  /// or boundary loop differs from the previous one, or `reuse` has the wrong length.
  BiharmonicCoordinates(const Pattern& pattern, const BiharmonicCoordinates& previous,
                        const std::vector<bool>& reuse);

  int num_pieces() const { return static_cast<int>(pieces_.size()); }
  const PieceBiharmonicCoordinates& piece(int k) const { return pieces_[k]; }
  /// Global pattern vertices n_p.
  int num_pattern_vertices() const { return offset_.back(); }
  /// Number of parameter points Σ n_b; p has twice as many entries.
  int num_parameter_points() const { return static_cast<int>(parameter_vertices_.size()); }
  int num_parameters() const { return 2 * num_parameter_points(); }
  /// Global pattern vertex of every parameter point (length Σ n_b).
  const std::vector<int>& parameter_vertices() const { return parameter_vertices_; }
  /// First global pattern vertex of each piece (+ n_p at the end).
  const std::vector<int>& piece_offset() const { return offset_; }

  /// p read off stacked rest positions (n_p×2, m): the boundary vertices' positions.
  VecX parameters(const Points2& rest) const;
  /// Xbar = W p (n_p×2, m) for p of length num_parameters().
  Points2 rest_positions(const VecX& p) const;
  /// Wᵀ g: a gradient with respect to Xbar (flat, 2·n_p, DOF 2·v + k) pulled back to p
  /// (flat, num_parameters()).
  VecX pull_back(const VecX& d_rest) const;
  /// W as a sparse (2·n_p) × num_parameters() matrix over the flat layouts (for tests and
  /// for building ∂g/∂p explicitly).
  SparseMatrix matrix() const;

 private:
  std::vector<PieceBiharmonicCoordinates> pieces_;
  std::vector<int> offset_;              // piece offsets in pattern vertices (+ n_p)
  std::vector<int> parameter_offset_;    // piece offsets in parameter points (+ total)
  std::vector<int> parameter_vertices_;  // global pattern vertex per parameter point
};

}  // namespace tightfit
