#pragma once
/// Seam stiffening (paper Eq. 12): one tensile spring per seam edge and per seam side,
///   U = Σ_edges ½ w t E_seam / l0 (l - l0)²,
/// where l0 = |Xbar_b - Xbar_a| is the rest length of the edge on THAT side's pattern
/// piece and l = |x_B - x_A| the deformed length between the garment vertices A, B the
/// two pattern vertices are welded into. The spring constant k = w t E_seam / l0 is in N/m.
/// A spring whose two ends coincide in 3D (l = 0) has no direction; it then contributes
/// zero gradient and zero Hessian (its energy is still ½ k l0²).
#include <array>
#include <memory>
#include <vector>

#include "tightfit/garment/garment_topology.hpp"
#include "tightfit/physics/rest_dependent_energy.hpp"

namespace tightfit {

/// Seam material: w t E_seam is the seam's axial stiffness (N).
struct SeamMaterial {
  double width = 0.0;           ///< w, m
  double depth = 0.0;           ///< t, m
  double youngs_modulus = 0.0;  ///< E_seam, Pa
};

class SeamSpringEnergy : public RestDependentEnergy {
 public:
  /// The seam springs of a welded garment: its seam edges and vertex map (shared, not
  /// copied), reading the rest positions `rest` (n_p×2, m; bound, not copied:
  /// rest_dependent_energy.hpp). Throws InputError when `rest` does not have one row per
  /// pattern vertex or gives a seam edge zero length, or w, t <= 0 or E_seam < 0.
  SeamSpringEnergy(std::shared_ptr<const GarmentTopology> topology, const Points2& rest,
                   SeamMaterial material);
  SeamSpringEnergy(std::shared_ptr<const GarmentTopology>, const Points2&&, SeamMaterial) = delete;
  /// Springs over raw arrays: `edges` pairs of pattern vertices (one per seam edge per
  /// side); `rest` n_p×2 (bound); `pattern_to_garment` n_p garment ids in
  /// [0, num_garment_vertices). Throws InputError for indices out of range, and as above.
  SeamSpringEnergy(std::vector<std::array<int, 2>> edges, const Points2& rest,
                   std::vector<int> pattern_to_garment, int num_garment_vertices,
                   SeamMaterial material);
  SeamSpringEnergy(std::vector<std::array<int, 2>>, const Points2&&, std::vector<int>, int,
                   SeamMaterial) = delete;

  std::string name() const override { return "seam springs"; }
  double value(const VecX& x) const override;
  void add_gradient(const VecX& x, VecX& g) const override;
  void add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd = false) const override;

  void check_rest(const Points2& rest) const override;
  void add_gradient_rest(const VecX& x, VecX& g_rest) const override;
  void add_mixed_rest(const VecX& x, std::vector<Triplet>& H) const override;

  int num_springs() const { return static_cast<int>(edges().size()); }
  const std::vector<std::array<int, 2>>& edges() const { return topology_->seam_edges; }
  const SeamMaterial& material() const { return material_; }
  /// w t E_seam (N): the spring constant of an edge is this over its rest length.
  double axial_stiffness() const {
    return material_.width * material_.depth * material_.youngs_modulus;
  }

 private:
  void check_x(const VecX& x) const;

  std::shared_ptr<const GarmentTopology> topology_;
  SeamMaterial material_;
};

}  // namespace tightfit
