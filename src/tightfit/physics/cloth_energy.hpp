#pragma once
/// Cloth: relaxed StVK constant-strain triangles (paper Eq. 5-11),
///   U = Σ_e t A_e W_cloth(C_e),   C_e = F_eᵀF_e,   F_e = Ds Dm⁻¹ (3×2),
/// with A_e the rest area and W_cloth the smoothed relaxed density of relaxed_stvk.hpp.
///
/// Triangles are over PATTERN vertices (each with its own 2D rest position Xbar); a map
/// sends each pattern vertex to its GARMENT vertex, where seams weld several pattern
/// vertices into one 3D vertex. x holds the garment positions (3·n_garment).
///
/// Implementation: per element the energy is written in terms of the two edge metrics
/// G = DsᵀDs (deformed) and M = DmᵀDm (rest): C has I1 = tr(G M⁻¹), I2 = det G / det M and
/// A = sqrt(det M)/2, so U_e = t Φ(G, M). Derivatives with respect to x and Xbar go
/// through G and M only (quadratic in positions), which gives the x-Hessian and the
/// mixed ∂²U/∂x∂Xbar from one 6×6 Hessian of Φ. The energy does not depend on the rest
/// triangle's orientation in the plane.
#include <vector>

#include "tightfit/physics/relaxed_stvk.hpp"
#include "tightfit/physics/rest_dependent_energy.hpp"

namespace tightfit {

class ClothEnergy : public RestDependentEnergy {
 public:
  /// `triangles` m×3 over pattern vertices; `rest` n_p×2 rest positions (m);
  /// `pattern_to_garment` n_p garment vertex ids in [0, num_garment_vertices).
  /// Throws InputError on an index out of range or a zero-area rest triangle, and for
  /// invalid material constants.
  ClothEnergy(Triangles triangles, Points2 rest, std::vector<int> pattern_to_garment,
              int num_garment_vertices, ClothMaterial material = {});

  std::string name() const override { return "cloth"; }
  double value(const VecX& x) const override;
  void add_gradient(const VecX& x, VecX& g) const override;
  void add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd = false) const override;

  int num_pattern_vertices() const override { return static_cast<int>(rest_.rows()); }
  const Points2& rest() const override { return rest_; }
  void set_rest(const Points2& rest) override;
  void add_gradient_rest(const VecX& x, VecX& g_rest) const override;
  void add_mixed_rest(const VecX& x, std::vector<Triplet>& H) const override;

  int num_garment_vertices() const { return num_garment_; }
  int num_triangles() const { return static_cast<int>(triangles_.rows()); }
  /// Triangles over pattern vertices (m×3).
  const Triangles& triangles() const { return triangles_; }
  /// The same triangles over garment vertices (for the 3D garment mesh).
  Triangles garment_triangles() const;
  const std::vector<int>& pattern_to_garment() const { return pattern_to_garment_; }
  const ClothMaterial& material() const { return law_.material(); }
  const RelaxedStVK& law() const { return law_; }
  /// Rest area of triangle e (m²).
  double rest_area(int e) const;
  /// Deformation gradient F = Ds Dm⁻¹ (3×2) of triangle e at x, in the rest frame of
  /// the pattern plane.
  Mat32 deformation_gradient(const VecX& x, int e) const;

 private:
  void check_x(const VecX& x) const;
  void validate_rest(const Points2& rest) const;

  Triangles triangles_;
  Points2 rest_;
  std::vector<int> pattern_to_garment_;
  int num_garment_ = 0;
  RelaxedStVK law_;
};

}  // namespace tightfit
