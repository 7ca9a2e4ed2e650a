#include "tightfit/physics/garment_energies.hpp"

namespace tightfit {

GarmentEnergies::GarmentEnergies(std::shared_ptr<const GarmentTopology> topology,
                                 const Points2& rest, const ClothMaterial& fabric,
                                 const SeamMaterial& seam)
    : cloth_(topology, rest, fabric) {
  if (seam.youngs_modulus > 0.0 && !topology->seam_edges.empty())
    seams_.emplace(std::move(topology), rest, seam);
}

std::vector<const RestDependentEnergy*> GarmentEnergies::all() const {
  std::vector<const RestDependentEnergy*> out{&cloth_};
  if (seams_) out.push_back(&*seams_);
  return out;
}

void GarmentEnergies::check_rest(const Points2& rest) const {
  for (const RestDependentEnergy* e : all()) e->check_rest(rest);
}

void GarmentEnergies::bind_rest(const Points2& rest) {
  check_rest(rest);
  cloth_.bind_rest(rest);
  if (seams_) seams_->bind_rest(rest);
}

}  // namespace tightfit
