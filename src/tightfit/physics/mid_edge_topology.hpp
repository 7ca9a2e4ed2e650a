#pragma once
/// Edge topology of the mid-edge shape operator system (Grinspun et al. 2006, Eq. 32-33;
/// see mid_edge_shape_operator.hpp): one unknown φ per mesh edge, and per face edge
/// (face f, edge i from corner i to corner i+1) the edge's unknown, its sign s_i (+1 in
/// the edge's first face, −1 in its second) and what lies across it. Shared by
/// MidEdgeShapeOperator and the pressure objective, so both number and orient the edge
/// unknowns the same way.
#include <array>
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

class MidEdgeTopology {
 public:
  /// `faces` m×3 indices in [0, num_vertices), consistently oriented. Edge unknowns are
  /// numbered as SurfaceTopology numbers the mesh's edges (by vertex pair: a numbering
  /// that keeps the sparse Cholesky factor of the φ system small).
  /// Throws InputError (with `source` naming the mesh) for out-of-range indices, faces
  /// repeating a vertex, edges with more than two faces and interior edges whose faces
  /// disagree on orientation.
  MidEdgeTopology(const Triangles& faces, int num_vertices,
                  const std::string& source = "garment mesh (shape operator)");

  const Triangles& faces() const { return faces_; }  ///< m×3, as given
  int num_faces() const { return static_cast<int>(faces_.rows()); }
  int num_vertices() const { return num_vertices_; }
  int num_edges() const { return static_cast<int>(edges_.size()); }

  /// Index of the edge unknown of face edge i (0..2) of `face`.
  int edge(int face, int i) const { return unknown_[3 * face + i]; }
  /// s_i of face edge i: +1 in the edge's first face, −1 in its second.
  int sign(int face, int i) const { return sign_[3 * face + i]; }
  /// The face edge 3·g + j on the other side of face edge i, −1 on a boundary edge.
  int across(int face, int i) const { return across_[3 * face + i]; }
  /// The vertex of the face across face edge i that is not on the edge, −1 on a
  /// boundary edge.
  int across_vertex(int face, int i) const {
    const int h = across_[3 * face + i];
    return h < 0 ? -1 : faces_(h / 3, (h % 3 + 2) % 3);
  }
  bool is_boundary(int face, int i) const { return across_[3 * face + i] < 0; }

  /// The three edge unknowns, signs and across-vertices of `face`.
  std::array<int, 3> edges(int face) const { return triple(unknown_, face); }
  std::array<int, 3> signs(int face) const { return triple(sign_, face); }
  std::array<int, 3> across_vertices(int face) const {
    return {across_vertex(face, 0), across_vertex(face, 1), across_vertex(face, 2)};
  }

  /// Per edge unknown, its face edge 3·f + i in its first face.
  const std::vector<int>& edge_face_edges() const { return edges_; }

 private:
  static std::array<int, 3> triple(const std::vector<int>& v, int face) {
    return {v[3 * face], v[3 * face + 1], v[3 * face + 2]};
  }

  Triangles faces_;
  int num_vertices_ = 0;
  std::vector<int> unknown_;  // per face edge (3·face + i)
  std::vector<int> sign_;     // per face edge
  std::vector<int> across_;   // per face edge: 3·g + j across, −1 on the boundary
  std::vector<int> edges_;    // per edge unknown: its face edge in its first face
};

}  // namespace tightfit
