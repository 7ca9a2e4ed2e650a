#pragma once
/// Cloth: relaxed StVK constant-strain triangles (paper Eq. 5-11),
///   U = Σ_e t A_e W_cloth(C_e),   C_e = F_eᵀF_e,   F_e = Ds Dm⁻¹ (3×2),
/// with A_e the rest area and W_cloth the smoothed relaxed density of relaxed_stvk.hpp, or
/// the measured orthotropic density of fabric_law.hpp in the piece's grain frame.
///
/// Triangles are over PATTERN vertices (each with its own 2D rest position Xbar); a map
/// sends each pattern vertex to its GARMENT vertex, where seams weld several pattern
/// vertices into one 3D vertex. x holds the garment positions (3·n_garment).
///
/// Implementation: per element the energy is written in terms of the two edge metrics
/// G = DsᵀDs (deformed) and M = DmᵀDm (rest): C has I1 = tr(G M⁻¹), I2 = det G / det M and
/// A = sqrt(det M)/2, so U_e = t Φ(G, M). Derivatives with respect to x and Xbar go
/// through G and M only (quadratic in positions), which gives the x-Hessian and the
/// mixed ∂²U/∂x∂Xbar from one 6×6 Hessian of Φ. The isotropic energy does not depend on
/// the rest triangle's orientation in the plane; the measured one does (C = Pᵀ G P,
/// P = Dm⁻¹, in the pattern frame), and its rest derivatives are taken with respect to
/// the rest corners by forward automatic differentiation.
#include <memory>
#include <vector>

#include "tightfit/garment/garment_topology.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/physics/rest_dependent_energy.hpp"

namespace tightfit {

class ClothEnergy : public RestDependentEnergy {
 public:
  /// The cloth of a welded garment: its pattern triangles and vertex map (shared, not
  /// copied), reading the rest positions `rest` (n_p×2, m; bound, not copied:
  /// rest_dependent_energy.hpp). Throws InputError when `rest` does not have one row per
  /// pattern vertex or has a zero-area triangle, and for invalid material constants.
  ClothEnergy(std::shared_ptr<const GarmentTopology> topology, const Points2& rest,
              ClothMaterial material = {});
  ClothEnergy(std::shared_ptr<const GarmentTopology>, const Points2&&, ClothMaterial = {}) = delete;
  /// Cloth over raw arrays (a single element, a test mesh): `triangles` m×3 over pattern
  /// vertices; `rest` n_p×2 (bound); `pattern_to_garment` n_p garment vertex ids in
  /// [0, num_garment_vertices). Throws InputError on an index out of range, and as above.
  ClothEnergy(Triangles triangles, const Points2& rest, std::vector<int> pattern_to_garment,
              int num_garment_vertices, ClothMaterial material = {});
  ClothEnergy(Triangles, const Points2&&, std::vector<int>, int, ClothMaterial = {}) = delete;

  std::string name() const override { return "cloth"; }
  double value(const VecX& x) const override;
  void add_gradient(const VecX& x, VecX& g) const override;
  void add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd = false) const override;
  /// One 9×9 matrix per triangle, over its three garment vertices.
  bool add_element_hessians(const VecX& x, std::vector<ElementMatrices>& H,
                            bool project_psd = false) const override;

  void check_rest(const Points2& rest) const override;
  void add_gradient_rest(const VecX& x, VecX& g_rest) const override;
  void add_mixed_rest(const VecX& x, std::vector<Triplet>& H) const override;

  int num_garment_vertices() const { return topology_->num_garment_vertices; }
  int num_triangles() const { return topology_->num_triangles(); }
  /// The connectivity the energy runs over.
  const GarmentTopology& topology() const { return *topology_; }
  /// Triangles over pattern vertices (m×3).
  const Triangles& triangles() const { return topology_->pattern_triangles; }
  /// The same triangles over garment vertices (for the 3D garment mesh).
  const Triangles& garment_triangles() const { return topology_->garment_triangles; }
  const std::vector<int>& pattern_to_garment() const { return topology_->pattern_to_garment; }
  const ClothMaterial& material() const { return law_.material(); }
  const FabricLaw& law() const { return law_; }
  /// Rest area of triangle e (m²).
  double rest_area(int e) const;
  /// Deformation gradient F = Ds Dm⁻¹ (3×2) of triangle e at x, in the rest frame of
  /// the pattern plane.
  Mat32 deformation_gradient(const VecX& x, int e) const;

 private:
  void check_x(const VecX& x) const;

  std::shared_ptr<const GarmentTopology> topology_;
  FabricLaw law_;
};

}  // namespace tightfit
