#include "tightfit/geometry/mesh_components.hpp"

#include <algorithm>
#include <numeric>

namespace tightfit {
namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

}  // namespace

std::vector<MeshComponent> connected_components(const TriMesh& mesh) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < nf; ++f)
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, mesh.faces(f, 0)), b = find_root(parent, mesh.faces(f, k));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<int> component_of_root(nv, -1);
  std::vector<MeshComponent> out;
  for (int f = 0; f < nf; ++f) {
    const int r = find_root(parent, mesh.faces(f, 0));
    if (component_of_root[r] < 0) {
      component_of_root[r] = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[component_of_root[r]].faces.push_back(f);
  }
  std::vector<int> local(nv, -1);
  for (MeshComponent& c : out) {
    std::vector<int> used;
    c.mesh.faces.resize(static_cast<Eigen::Index>(c.faces.size()), 3);
    for (std::size_t i = 0; i < c.faces.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.faces(c.faces[i], k);
        if (local[v] < 0) {
          local[v] = static_cast<int>(used.size());
          used.push_back(v);
        }
        c.mesh.faces(static_cast<Eigen::Index>(i), k) = local[v];
      }
    c.mesh.vertices.resize(static_cast<Eigen::Index>(used.size()), 3);
    for (std::size_t i = 0; i < used.size(); ++i) {
      c.mesh.vertices.row(static_cast<Eigen::Index>(i)) = mesh.vertices.row(used[i]);
      local[used[i]] = -1;
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const MeshComponent& a, const MeshComponent& b) {
    return a.faces.size() > b.faces.size();
  });
  return out;
}

}  // namespace tightfit
