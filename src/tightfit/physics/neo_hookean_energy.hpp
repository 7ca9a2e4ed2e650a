#pragma once
/// Compressible Neo-Hookean solid on linear tetrahedra (paper Eq. 1-4, with the trace
/// that Eq. 3 omits):
///   W(F) = μ/2 (J^(-2/3) tr(FᵀF) - 3) + κ/2 (J - 1)²,   J = det F,
///   U = Σ_e V_e W(F_e),   F_e = Ds Dm⁻¹ (constant per tet),
/// with V_e the rest volume. Constants from Young's modulus E and Poisson ratio ν:
///   μ = E / (2(1+ν))      (shear modulus),
///   κ = E / (3(1-2ν))     (bulk modulus).
/// The paper writes the Lamé λ in front of the volumetric term; we use κ because with
/// the isochoric first term the small-strain limit of this W is linear elasticity with
/// exactly (E, ν) only for κ (with λ the effective bulk modulus would be λ instead of
/// λ + 2μ/3: 1.3 % low at ν = 0.49).
/// Inverted or flat elements (J <= 0) have energy +infinity, so a line search rejects
/// such states; gradient and Hessian are not defined there and throw SolverError.
#include <array>
#include <vector>

#include "tightfit/physics/energy.hpp"

namespace tightfit {

/// Body material (paper Sec. 6.2 defaults).
struct NeoHookeanMaterial {
  double youngs_modulus = 24.78e3;  ///< E, Pa
  double poisson_ratio = 0.49;      ///< ν, in (-1, 0.5)

  /// μ = E / (2(1+ν)), Pa.
  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  /// κ = E / (3(1-2ν)), Pa.
  double bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
};

class NeoHookeanEnergy : public Energy {
 public:
  /// `rest` n×3 rest positions (m); `tets` m×4 indices with positive rest orientation
  /// (v1-v0)·((v2-v0)×(v3-v0)) > 0. x then has 3n entries. Throws InputError for an
  /// index out of range, a non-positive rest volume or an invalid material.
  NeoHookeanEnergy(const Points3& rest, const Tetrahedra& tets, NeoHookeanMaterial material = {});

  std::string name() const override { return "neo-hookean"; }
  double value(const VecX& x) const override;
  void add_gradient(const VecX& x, VecX& g) const override;
  void add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd = false) const override;
  /// One 12×12 matrix per tet, over its four vertices.
  bool add_element_hessians(const VecX& x, std::vector<ElementMatrices>& H,
                            bool project_psd = false) const override;

  int num_vertices() const { return num_vertices_; }
  int num_tets() const { return static_cast<int>(tets_.size()); }
  const NeoHookeanMaterial& material() const { return material_; }
  /// Rest volume of tet e (m³).
  double rest_volume(int e) const { return volume_[e]; }
  /// Deformation gradient of tet e at x.
  Mat3 deformation_gradient(const VecX& x, int e) const;

 private:
  void check_size(const VecX& v) const;
  /// Tet e's 12×12 Hessian at x (projected onto the PSD cone with `project_psd`).
  Eigen::Matrix<double, 12, 12> element_hessian(const VecX& x, int e, bool project_psd) const;

  int num_vertices_ = 0;
  NeoHookeanMaterial material_;
  double mu_ = 0.0;
  double kappa_ = 0.0;
  std::vector<std::array<int, 4>> tets_;
  std::vector<Mat3> rest_inverse_;  // Dm⁻¹ per tet
  std::vector<double> volume_;
};

}  // namespace tightfit
