#include "tightfit/objectives/pressure_regions.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "tightfit/common/error.hpp"

namespace tightfit {

PressureRegions::PressureRegions(const Garment& garment, std::vector<PressureRegion> regions,
                                 const std::string& source, const SkinWeights* rig, double radius)
    : regions_(std::move(regions)), triangles_(garment.topology->garment_triangles) {
  bone_fields_.resize(regions_.size());
  const std::vector<PatternPiece>& pieces = garment.pattern.pieces;
  std::set<std::string> names;
  std::vector<std::vector<char>> selects(regions_.size(), std::vector<char>(pieces.size(), 0));
  for (std::size_t r = 0; r < regions_.size(); ++r) {
    PressureRegion& region = regions_[r];
    const std::string what = "pressure region \"" + region.name + "\"";
    if (region.name.empty()) throw InputError(source, "a pressure region has no name");
    if (!names.insert(region.name).second)
      throw InputError(source, "two pressure regions are named \"" + region.name + "\"");
    if (!std::isfinite(region.min_pa) || !std::isfinite(region.max_pa) ||
        region.min_pa > region.max_pa)
      throw InputError(source, what + ": the range must be finite with min <= max");
    if (!std::isfinite(region.transition) || region.transition < 0.0)
      throw InputError(source, what + ": the transition width must be >= 0");
    for (std::optional<RegionPlane>* plane : {&region.above, &region.below}) {
      if (!*plane) continue;
      const double length = (*plane)->normal.norm();
      if (!(length > 0.0) || !(*plane)->point.allFinite())
        throw InputError(source,
                         what + ": a band plane needs a finite point and a non-zero normal");
      (*plane)->normal /= length;
    }
    if (!region.bones.empty()) {
      if (rig == nullptr)
        throw InputError(source, what +
                                     " names bones but the scene has no rig "
                                     "(\"pressure\": {\"rig\": {\"mesh\", \"weights\"}})");
      if (!(radius > 0.0)) throw InputError(source, "the rig's interpolation radius must be > 0");
      bone_fields_[r] = std::make_shared<const PointField>(rig->vertices,
                                                           rig->summed(region.bones, what), radius);
    }
    if (region.pieces.empty()) {
      std::fill(selects[r].begin(), selects[r].end(), 1);
      continue;
    }
    for (const std::string& name : region.pieces) {
      std::size_t k = 0;
      while (k < pieces.size() && pieces[k].name != name) ++k;
      if (k == pieces.size())
        throw InputError(source, what + ": the garment has no piece \"" + name + "\"");
      selects[r][k] = 1;
    }
  }
  candidates_.resize(static_cast<std::size_t>(triangles_.rows()));
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e)
    for (std::size_t r = 0; r < regions_.size(); ++r)
      if (selects[r][garment.topology->triangle_piece[e]])
        candidates_[e].push_back(static_cast<int>(r));
}

MatX PressureRegions::weights(const VecX& x) const {
  MatX w = MatX::Zero(size(), triangles_.rows());
  for (Eigen::Index e = 0; e < triangles_.rows(); ++e) {
    std::array<Vec3, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = x.segment<3>(3 * triangles_(e, k));
    for (int r : candidates_[e]) w(r, e) = band_weight<double>(r, corners);
  }
  return w;
}

void PressureRegions::check_covered(const VecX& x, const std::string& source) const {
  const MatX w = weights(x);
  std::string uncovered;
  for (int r = 0; r < size(); ++r)
    if (!(w.row(r).maxCoeff() > 0.0))
      uncovered += (uncovered.empty() ? "\"" : ", \"") + regions_[r].name + "\"";
  if (!uncovered.empty())
    throw InputError(source, "no garment triangle lies in pressure region " + uncovered +
                                 " (check its pieces, bones and band planes)");
}

}  // namespace tightfit
