#include "tightfit/physics/mid_edge_topology.hpp"

#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit {

MidEdgeTopology::MidEdgeTopology(const Triangles& faces, int num_vertices,
                                 const std::string& source)
    : faces_(faces), num_vertices_(num_vertices) {
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= num_vertices)
        throw InputError(source, "face " + std::to_string(f) + " has vertex index " +
                                     std::to_string(faces(f, k)) + " outside [0, " +
                                     std::to_string(num_vertices) + ")");
    if (faces(f, 0) == faces(f, 1) || faces(f, 1) == faces(f, 2) || faces(f, 2) == faces(f, 0))
      throw InputError(source, "face " + std::to_string(f) + " repeats a vertex");
  }
  const SurfaceTopology topo(faces, num_vertices);
  if (!topo.non_manifold_edges().empty())
    throw InputError(source, std::to_string(topo.non_manifold_edges().size()) +
                                 " edges have more than two faces");
  if (!topo.inconsistently_oriented_edges().empty())
    throw InputError(source, "faces are not consistently oriented at " +
                                 std::to_string(topo.inconsistently_oriented_edges().size()) +
                                 " edges");
  const int m = topo.num_faces();
  unknown_.assign(3 * m, -1);
  sign_.assign(3 * m, 1);
  across_.assign(3 * m, -1);
  edges_.assign(topo.num_edges(), -1);
  for (int f = 0; f < m; ++f)
    for (int i = 0; i < 3; ++i) {
      const int e = topo.face_edge(f, i);
      unknown_[3 * f + i] = e;
      if (edges_[e] < 0)
        edges_[e] = 3 * f + i;  // faces in order: the edge's first face
      else
        sign_[3 * f + i] = -1;
      if (topo.edge_valence(e) != 2) continue;  // boundary edge
      const SurfaceTopology::Across a = topo.across(f, i);
      across_[3 * f + i] = 3 * a.face + a.edge_in_face;
    }
}

}  // namespace tightfit
