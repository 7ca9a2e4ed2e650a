#pragma once
/// The energies of a garment that depend on its pattern rest positions: the cloth
/// (cloth_energy.hpp) and, when the seam material is on and the garment has seams, the
/// seam springs (seam_spring_energy.hpp). Both run over one shared GarmentTopology and
/// read one rest array (n_p×2, m) that they are bound to and do not copy: the
/// simulation's rest array, or the rest of the design state a design term evaluates.
#include <memory>
#include <optional>
#include <vector>

#include "tightfit/garment/garment_topology.hpp"
#include "tightfit/physics/cloth_energy.hpp"
#include "tightfit/physics/seam_spring_energy.hpp"

namespace tightfit {

class GarmentEnergies {
 public:
  /// Throws InputError when `rest` does not fit the topology (rest_dependent_energy.hpp)
  /// or a material is invalid. `rest` must outlive this object (or the next bind_rest).
  GarmentEnergies(std::shared_ptr<const GarmentTopology> topology, const Points2& rest,
                  const ClothMaterial& fabric, const SeamMaterial& seam);
  GarmentEnergies(std::shared_ptr<const GarmentTopology>, const Points2&&, const ClothMaterial&,
                  const SeamMaterial&) = delete;

  const ClothEnergy& cloth() const { return cloth_; }
  /// The seam springs, or null when the seam modulus is 0 or the garment has no seams.
  const SeamSpringEnergy* seams() const { return seams_ ? &*seams_ : nullptr; }
  /// Cloth, then the seam springs when present.
  std::vector<const RestDependentEnergy*> all() const;

  /// Throws InputError, before any energy changes, when `rest` does not fit one of them.
  void check_rest(const Points2& rest) const;
  /// Binds every energy to `rest` after check_rest.
  void bind_rest(const Points2& rest);
  void bind_rest(const Points2&&) = delete;

 private:
  ClothEnergy cloth_;
  std::optional<SeamSpringEnergy> seams_;
};

}  // namespace tightfit
