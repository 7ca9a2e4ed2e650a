#pragma once
/// Edge and face adjacency of a triangle mesh (topology only, no positions).
///
/// Conventions (shared with the limit surface, docs/design.md §6): face edge i runs from
/// corner i to corner (i+1)%3. Edges are undirected; their ids are dense in
/// [0, num_edges()) and ordered by their sorted vertex pair (lo, hi).
///
/// The class accepts any index array with indices in [0, num_vertices): non-manifold
/// edges (more than two faces), non-manifold vertices and degenerate faces (a repeated
/// index) are represented, not rejected; mesh_validation.hpp reports them.
#include <array>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

class SurfaceTopology {
 public:
  /// `faces` m×3 vertex indices in [0, num_vertices). Throws std::invalid_argument if
  /// an index is out of range or num_vertices < 0 (validate input files first).
  SurfaceTopology(const Triangles& faces, int num_vertices);

  int num_vertices() const { return num_vertices_; }
  int num_faces() const { return static_cast<int>(face_edges_.size()); }
  int num_edges() const { return static_cast<int>(edge_vertices_.size()); }

  /// Edge id of face edge i (i in 0..2), which runs from corner i to corner (i+1)%3.
  int face_edge(int face, int i) const { return face_edges_[face][i]; }
  /// Vertex indices of an edge, sorted (lo, hi).
  std::array<int, 2> edge_vertices(int edge) const { return edge_vertices_[edge]; }
  /// The first two faces of an edge in face order; [1] == -1 on a boundary edge.
  /// On a non-manifold edge (edge_valence > 2) use edge_all_faces.
  std::array<int, 2> edge_faces(int edge) const;
  /// Number of face edges that use this edge: 1 on the boundary, 2 inside a manifold,
  /// more on a non-manifold edge.
  int edge_valence(int edge) const { return edge_start_[edge + 1] - edge_start_[edge]; }
  /// All faces of an edge (with repetition if one degenerate face uses it twice).
  std::vector<int> edge_all_faces(int edge) const;
  /// True when the edge has one face (a hole / open boundary).
  bool is_boundary_edge(int edge) const { return edge_valence(edge) == 1; }

  /// Neighbour across a face edge: the other face and the index (0..2) of the shared
  /// edge in that face.
  struct Across {
    int face;
    int edge_in_face;
  };
  /// The neighbour across face edge i. Returns {-1, -1} when the edge has no unique
  /// neighbour: on a boundary edge and also on a non-manifold edge (> 2 faces).
  Across across(int face, int i) const;

  /// Faces incident to vertex v, ascending, each once.
  const std::vector<int>& vertex_faces(int v) const { return vertex_faces_[v]; }
  /// Edges incident to vertex v, ascending.
  const std::vector<int>& vertex_edges(int v) const { return vertex_edges_[v]; }
  /// One-ring vertices of v (the other endpoints of its edges), ascending.
  std::vector<int> vertex_neighbors(int v) const;
  /// The edge between vertices a and b, or -1 if there is none.
  int find_edge(int a, int b) const;

  /// True when the mesh has no boundary edges.
  bool is_closed() const;
  /// Boundary edge ids, ascending.
  std::vector<int> boundary_edges() const;
  /// Each boundary loop as vertex indices in the order of the face edges on the
  /// boundary (following face orientation: the interior lies to the left seen from
  /// the front side). A loop is not closed by repeating its first vertex. Loops start
  /// at the boundary edge with the lowest id not yet used.
  std::vector<std::vector<int>> boundary_loops() const;
  /// Edges with more than two faces, ascending.
  std::vector<int> non_manifold_edges() const;
  /// Vertices whose incident faces form more than one fan, ascending. Two faces are
  /// in the same fan when they are connected through edges incident to the vertex
  /// (any such edge, manifold or not). An isolated vertex (no faces) is not reported.
  std::vector<int> non_manifold_vertices() const;
  /// Manifold interior edges whose two faces traverse the edge in the same direction
  /// (the faces disagree on orientation), ascending.
  std::vector<int> inconsistently_oriented_edges() const;
  /// Vertices used by no face, ascending.
  std::vector<int> isolated_vertices() const;

 private:
  int num_vertices_ = 0;
  Triangles faces_;
  std::vector<std::array<int, 3>> face_edges_;
  std::vector<std::array<int, 2>> edge_vertices_;
  // Face edges (encoded as 3*face + i) of each edge: edge_half_[edge_start_[e] ..
  // edge_start_[e+1]).
  std::vector<int> edge_start_;
  std::vector<int> edge_half_;
  std::vector<std::vector<int>> vertex_faces_;
  std::vector<std::vector<int>> vertex_edges_;
};

}  // namespace tightfit
