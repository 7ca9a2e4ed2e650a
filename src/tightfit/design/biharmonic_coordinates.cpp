#include "tightfit/design/biharmonic_coordinates.hpp"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "tightfit/common/error.hpp"
#include "tightfit/common/sparse_cholesky.hpp"

namespace tightfit {
namespace {

/// Rotates a 2D vector by +90°.
Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }

std::string source_of(const PatternPiece& piece) { return "pattern piece " + piece.name; }

void validate(const PatternPiece& piece) {
  const std::string src = source_of(piece);
  const Eigen::Index n = piece.rest.rows();
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      if (piece.triangles(t, k) < 0 || piece.triangles(t, k) >= n)
        throw InputError(src, "triangle " + std::to_string(t) + " has vertex " +
                                  std::to_string(piece.triangles(t, k)) + " outside [0, " +
                                  std::to_string(n) + ")");
  if (piece.boundary.size() < 3)
    throw InputError(src, "boundary loop has " + std::to_string(piece.boundary.size()) +
                              " vertices, at least 3 are needed");
  std::vector<char> seen(n, 0);
  for (int v : piece.boundary_vertices()) {
    if (v < 0 || v >= n)
      throw InputError(
          src, "boundary vertex " + std::to_string(v) + " outside [0, " + std::to_string(n) + ")");
    if (seen[v]) throw InputError(src, "boundary loop repeats vertex " + std::to_string(v));
    seen[v] = 1;
  }
}

/// L̃ = −K + N (n×n) and the lumped mass diagonal (see the header).
void weak_laplacian(const PatternPiece& piece, SparseMatrix& laplacian, VecX& mass) {
  const Points2& x = piece.rest;
  const Eigen::Index n = x.rows();
  std::vector<Triplet> trip;
  trip.reserve(9 * static_cast<std::size_t>(piece.triangles.rows()) * 3);
  mass = VecX::Zero(n);
  // Count the triangles of every undirected edge to find mesh-boundary edges.
  std::map<std::pair<int, int>, int> edge_count;
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = piece.triangles(t, i), b = piece.triangles(t, (i + 1) % 3);
      ++edge_count[{std::min(a, b), std::max(a, b)}];
    }
  for (Eigen::Index t = 0; t < piece.triangles.rows(); ++t) {
    const std::array<int, 3> v = {piece.triangles(t, 0), piece.triangles(t, 1),
                                  piece.triangles(t, 2)};
    const std::array<Vec2, 3> p = {x.row(v[0]).transpose(), x.row(v[1]).transpose(),
                                   x.row(v[2]).transpose()};
    const Vec2 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const double twice_signed = e1.x() * e2.y() - e1.y() * e2.x();
    const double scale = e1.squaredNorm() + e2.squaredNorm();
    // Exact affine precision needs a valid triangulation: every triangle counter-clockwise.
    if (!(twice_signed > 1e-14 * scale))
      throw InputError(source_of(piece),
                       "triangle " + std::to_string(t) + " is degenerate or clockwise (inverted)");
    const double area = 0.5 * twice_signed;
    // ∇φ_i = perp(p_{i+2} − p_{i+1}) / (2 A).
    std::array<Vec2, 3> grad;
    for (int i = 0; i < 3; ++i) grad[i] = perp(p[(i + 2) % 3] - p[(i + 1) % 3]) / twice_signed;
    for (int i = 0; i < 3; ++i) {
      mass[v[i]] += area / 3.0;
      for (int j = 0; j < 3; ++j) trip.emplace_back(v[i], v[j], -area * grad[i].dot(grad[j]));
    }
    // Boundary term on mesh-boundary edges of this triangle: ∫_e φ_a ∂f/∂n = (ℓ/2) n·∇f.
    for (int i = 0; i < 3; ++i) {
      const int a = v[i], b = v[(i + 1) % 3];
      if (edge_count[{std::min(a, b), std::max(a, b)}] != 1) continue;
      const Vec2 d = p[(i + 1) % 3] - p[i];
      Vec2 ln = Vec2(d.y(), -d.x());  // ℓ·n, sign fixed below to point away from the face
      if (ln.dot(p[(i + 2) % 3] - p[i]) > 0.0) ln = -ln;
      for (int k = 0; k < 3; ++k) {
        const double w = 0.5 * ln.dot(grad[k]);
        trip.emplace_back(a, v[k], w);
        trip.emplace_back(b, v[k], w);
      }
    }
  }
  laplacian.resize(n, n);
  laplacian.setFromTriplets(trip.begin(), trip.end());
}

}  // namespace

PieceBiharmonicCoordinates::PieceBiharmonicCoordinates(const PatternPiece& piece)
    : boundary_(piece.boundary_vertices()) {
  validate(piece);
  const int n = static_cast<int>(piece.rest.rows());
  const int nb = static_cast<int>(boundary_.size());
  std::vector<int> column(n, -1);  // boundary column, or -1 for interior
  for (int j = 0; j < nb; ++j) column[boundary_[j]] = j;
  std::vector<int> interior;
  std::vector<int> interior_index(n, -1);
  for (int v = 0; v < n; ++v)
    if (column[v] < 0) {
      interior_index[v] = static_cast<int>(interior.size());
      interior.push_back(v);
    }
  weights_ = MatX::Zero(n, nb);
  for (int j = 0; j < nb; ++j) weights_(boundary_[j], j) = 1.0;
  if (interior.empty()) return;

  SparseMatrix lt;
  VecX mass;
  weak_laplacian(piece, lt, mass);
  for (int v = 0; v < n; ++v)
    if (!(mass[v] > 0.0))
      throw InputError(source_of(piece), "vertex " + std::to_string(v) + " is in no triangle");
  const SparseMatrix minv_lt = mass.cwiseInverse().asDiagonal() * lt;
  const SparseMatrix q = SparseMatrix(lt.transpose()) * minv_lt;

  const int ni = static_cast<int>(interior.size());
  std::vector<Triplet> qii_trip;
  MatX qib = MatX::Zero(ni, nb);
  for (int c = 0; c < q.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(q, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      if (interior_index[r] < 0) continue;
      if (interior_index[c] >= 0)
        qii_trip.emplace_back(interior_index[r], interior_index[c], it.value());
      else
        qib(interior_index[r], column[c]) += it.value();
    }
  SparseMatrix qii(ni, ni);
  qii.setFromTriplets(qii_trip.begin(), qii_trip.end());
  SparseCholesky solver;
  if (!solver.factorize(qii))
    throw SolverError("biharmonic coordinates of pattern piece " + piece.name +
                      ": Q_II is not positive definite");
  const MatX wi = -solver.solve_columns(qib);
  for (int i = 0; i < ni; ++i) weights_.row(interior[i]) = wi.row(i);
}

Points2 PieceBiharmonicCoordinates::apply(const Points2& boundary_positions) const {
  if (boundary_positions.rows() != num_boundary())
    throw std::invalid_argument("PieceBiharmonicCoordinates::apply: expected " +
                                std::to_string(num_boundary()) + " boundary positions");
  return weights_ * boundary_positions;
}

Points2 PieceBiharmonicCoordinates::apply_transpose(const Points2& per_vertex) const {
  if (per_vertex.rows() != num_vertices())
    throw std::invalid_argument("PieceBiharmonicCoordinates::apply_transpose: expected " +
                                std::to_string(num_vertices()) + " rows");
  return weights_.transpose() * per_vertex;
}

BiharmonicCoordinates::BiharmonicCoordinates(const Pattern& pattern) {
  offset_.push_back(0);
  parameter_offset_.push_back(0);
  pieces_.reserve(pattern.pieces.size());
  for (const PatternPiece& piece : pattern.pieces) {
    pieces_.emplace_back(piece);
    for (int v : piece.boundary_vertices()) parameter_vertices_.push_back(offset_.back() + v);
    offset_.push_back(offset_.back() + static_cast<int>(piece.rest.rows()));
    parameter_offset_.push_back(static_cast<int>(parameter_vertices_.size()));
  }
}

BiharmonicCoordinates::BiharmonicCoordinates(const Pattern& pattern,
                                             const BiharmonicCoordinates& previous,
                                             const std::vector<bool>& reuse) {
  if (reuse.size() != pattern.pieces.size() ||
      previous.num_pieces() != static_cast<int>(pattern.pieces.size()))
    throw std::invalid_argument("BiharmonicCoordinates: one reuse flag per piece is needed");
  offset_.push_back(0);
  parameter_offset_.push_back(0);
  pieces_.reserve(pattern.pieces.size());
  for (size_t k = 0; k < pattern.pieces.size(); ++k) {
    const PatternPiece& piece = pattern.pieces[k];
    if (reuse[k]) {
      const PieceBiharmonicCoordinates& old = previous.piece(static_cast<int>(k));
      if (old.num_vertices() != piece.rest.rows() || old.boundary() != piece.boundary_vertices())
        throw std::invalid_argument("BiharmonicCoordinates: reused piece " + piece.name +
                                    " has another mesh");
      pieces_.push_back(old);
    } else {
      pieces_.emplace_back(piece);
    }
    for (int v : piece.boundary_vertices()) parameter_vertices_.push_back(offset_.back() + v);
    offset_.push_back(offset_.back() + static_cast<int>(piece.rest.rows()));
    parameter_offset_.push_back(static_cast<int>(parameter_vertices_.size()));
  }
}

VecX BiharmonicCoordinates::parameters(const Points2& rest) const {
  if (rest.rows() != num_pattern_vertices())
    throw std::invalid_argument("BiharmonicCoordinates::parameters: expected " +
                                std::to_string(num_pattern_vertices()) + " rest positions");
  VecX p(num_parameters());
  for (int j = 0; j < num_parameter_points(); ++j)
    p.segment<2>(2 * j) = rest.row(parameter_vertices_[j]).transpose();
  return p;
}

Points2 BiharmonicCoordinates::rest_positions(const VecX& p) const {
  if (p.size() != num_parameters())
    throw std::invalid_argument("BiharmonicCoordinates::rest_positions: expected " +
                                std::to_string(num_parameters()) + " parameters");
  Points2 rest(num_pattern_vertices(), 2);
  for (int k = 0; k < num_pieces(); ++k) {
    const int nb = pieces_[k].num_boundary();
    const Eigen::Map<const Points2> pb(p.data() + 2 * parameter_offset_[k], nb, 2);
    rest.middleRows(offset_[k], pieces_[k].num_vertices()) = pieces_[k].weights() * pb;
  }
  return rest;
}

VecX BiharmonicCoordinates::pull_back(const VecX& d_rest) const {
  if (d_rest.size() != 2 * num_pattern_vertices())
    throw std::invalid_argument("BiharmonicCoordinates::pull_back: expected " +
                                std::to_string(2 * num_pattern_vertices()) + " entries");
  VecX out(num_parameters());
  for (int k = 0; k < num_pieces(); ++k) {
    const int n = pieces_[k].num_vertices();
    const int nb = pieces_[k].num_boundary();
    const Eigen::Map<const Points2> g(d_rest.data() + 2 * offset_[k], n, 2);
    Eigen::Map<Points2> gp(out.data() + 2 * parameter_offset_[k], nb, 2);
    gp = pieces_[k].weights().transpose() * g;
  }
  return out;
}

SparseMatrix BiharmonicCoordinates::matrix() const {
  std::vector<Triplet> trip;
  for (int k = 0; k < num_pieces(); ++k) {
    const MatX& w = pieces_[k].weights();
    for (Eigen::Index i = 0; i < w.rows(); ++i)
      for (Eigen::Index j = 0; j < w.cols(); ++j) {
        if (w(i, j) == 0.0) continue;
        for (int c = 0; c < 2; ++c)
          trip.emplace_back(2 * (offset_[k] + i) + c, 2 * (parameter_offset_[k] + j) + c, w(i, j));
      }
  }
  SparseMatrix m(2 * num_pattern_vertices(), num_parameters());
  m.setFromTriplets(trip.begin(), trip.end());
  return m;
}

}  // namespace tightfit
