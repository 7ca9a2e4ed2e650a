#include "tightfit/physics/seam_traction.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "tightfit/common/error.hpp"

namespace tightfit {

std::vector<SeamElement> seam_elements(const GarmentTopology& topology) {
  const Triangles& triangles = topology.pattern_triangles;
  std::map<std::pair<int, int>, std::vector<int>> edge_triangles;
  for (int e = 0; e < static_cast<int>(triangles.rows()); ++e)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(e, k), b = triangles(e, (k + 1) % 3);
      edge_triangles[{std::min(a, b), std::max(a, b)}].push_back(e);
    }
  std::vector<SeamElement> elements;
  for (const auto& [a, b] : topology.seam_edges) {
    const auto it = edge_triangles.find({std::min(a, b), std::max(a, b)});
    if (it == edge_triangles.end())
      throw InputError("seam traction", "seam edge (" + std::to_string(a) + ", " +
                                            std::to_string(b) +
                                            ") is not an edge of any pattern triangle");
    for (int e : it->second) elements.push_back({e, {a, b}});
  }
  return elements;
}

int triangle_corner(const Triangles& tri, int e, int v) {
  for (int k = 0; k < 3; ++k)
    if (tri(e, k) == v) return k;
  return -1;
}

VecX seam_normal_tractions(const GarmentTopology& topology,
                           const std::vector<SeamElement>& elements, const FabricLaw& law,
                           const VecX& x, const Points2& rest) {
  const Triangles& triangles = topology.pattern_triangles;
  VecX out(static_cast<Eigen::Index>(elements.size()));
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const SeamElement& el = elements[i];
    std::array<Vec3, 3> xs;
    std::array<Vec2, 3> rs;
    for (int k = 0; k < 3; ++k) {
      const int pv = triangles(el.triangle, k);
      xs[k] = x.segment<3>(3 * topology.pattern_to_garment[static_cast<size_t>(pv)]);
      rs[k] = rest.row(pv).transpose();
    }
    out[static_cast<Eigen::Index>(i)] =
        seam_traction_term<double>(law, xs, rs, triangle_corner(triangles, el.triangle, el.edge[0]),
                                   triangle_corner(triangles, el.triangle, el.edge[1]), true);
  }
  return out;
}

}  // namespace tightfit
