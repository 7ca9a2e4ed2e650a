#pragma once
/// The normal traction the cloth pulls on its seams with (paper Sec. 5.4, Eq. 36): per
/// seam-adjacent element — a seam edge with a pattern triangle that holds it — the
/// traction t (S n·n) per unit rest length of the seam (N/m), with n the unit rest-frame
/// normal of the edge in its piece, t the cloth thickness (m) and S = 2 ∂W_cloth/∂C (Pa)
/// the second Piola-Kirchhoff stress of the relaxed StVK law in the element (C = FᵀF,
/// F = Ds Dm⁻¹ in the piece's rest frame).
///
/// What the seam traction objective (objectives/seam_traction_objective.hpp) sums and
/// the seam statistics of a fit (report/seam_statistics.hpp) report: one definition for
/// both. The kernel is a template so that the objective can differentiate it.
#include <array>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/garment/garment_topology.hpp"
#include "tightfit/physics/autodiff.hpp"
#include "tightfit/physics/fabric_law.hpp"

namespace tightfit {

/// One seam-adjacent element: the triangle (index into GarmentTopology::
/// pattern_triangles) and the seam edge as global pattern vertices.
struct SeamElement {
  int triangle = -1;
  std::array<int, 2> edge{};
};

/// Every seam edge of `topology` (both sides of every seam) with each pattern triangle
/// that holds it, in the order of GarmentTopology::seam_edges. Throws InputError (source
/// "seam traction") when a seam edge is not an edge of any triangle.
std::vector<SeamElement> seam_elements(const GarmentTopology& topology);

/// Local corner index (0..2) of pattern vertex `v` in pattern triangle `e` of `tri`; −1
/// when the triangle does not hold it.
int triangle_corner(const Triangles& tri, int e, int v);

/// l0 · t (S n·n) of one element (N), or t (S n·n) alone (N/m) when `per_length`: the
/// triangle's garment positions `x` (m) and rest positions `r` (m), the seam edge from
/// corner `a` to corner `b`. With d = r_b − r_a and n = perp(d)/l0,
/// l0 S n·n = perp(d)ᵀ S perp(d) / l0.
template <typename S>
S seam_traction_term(const FabricLaw& law, const std::array<autodiff::Vec3T<S>, 3>& x,
                     const std::array<autodiff::Vec2T<S>, 3>& r, int a, int b, bool per_length) {
  using std::sqrt;
  autodiff::Mat2T<S> dm;
  autodiff::Mat32T<S> ds;
  for (int k = 0; k < 2; ++k) {
    dm.col(k) = r[k + 1] - r[0];
    ds.col(k) = x[k + 1] - x[0];
  }
  const autodiff::Mat32T<S> f = ds * autodiff::inverse2(dm);
  const autodiff::Mat2T<S> c = f.transpose() * f;
  const autodiff::Mat2T<S> stress = autodiff::second_piola(law, c);
  const autodiff::Vec2T<S> d = r[b] - r[a];
  autodiff::Vec2T<S> n;
  n << -d(1), d(0);
  const S l0 = sqrt(d.squaredNorm());
  const S snn = n.dot(stress * n);
  return law.material().thickness * (per_length ? S(snn / (l0 * l0)) : S(snn / l0));
}

/// The normal traction t (S n·n) per unit rest length (N/m) of every element of
/// `elements`, for garment positions `x` (3·n_g, x0 y0 z0 x1 ..., m) and pattern rest
/// positions `rest` (n_p×2, m) of `topology`'s garment.
VecX seam_normal_tractions(const GarmentTopology& topology,
                           const std::vector<SeamElement>& elements, const FabricLaw& law,
                           const VecX& x, const Points2& rest);

}  // namespace tightfit
