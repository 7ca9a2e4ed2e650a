#pragma once
/// Pressure targets by region (compression garments: a stocking's ankle, calf and thigh
/// bands; a mask's cheeks and forehead): where on the garment a target range applies.
///
/// A region selects garment triangles by piece, by a band of the body between two planes
/// and/or by skeleton bones. Its membership weight w_e ∈ [0, 1] of garment triangle e is
///   w_e = [piece of e selected] · S(d_above(c_e) / δ) · S(−d_below(c_e) / δ) · b(c_e),
/// with c_e the centroid of the DEFORMED triangle (m), d the signed distance (m) to a
/// plane (positive on the side its normal points to), S the C¹ smoothstep rising from 0
/// at −½ to 1 at +½ (3u² − 2u³, u = t + ½), and δ the band's transition width (m;
/// δ = 0 gives a hard step), and b the summed skin weight of the region's bones carried
/// from the rig's vertices to c_e by a smooth compact-kernel interpolation (PointField,
/// radius from the rig spec; b = 1 without bones): the surface "dominated" by the bones
/// is where b >= ½. The weight is a function of the garment positions, not of a
/// state frozen when the objective was built: a triangle that slides across a band's
/// plane moves smoothly from one target to the next, and the objective stays C¹.
/// Regions may overlap; the pressure objective sums them (pressure_objective.hpp).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "tightfit/body/skin_weights.hpp"
#include "tightfit/common/types.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/point_field.hpp"
#include "tightfit/objectives/pressure_region.hpp"
#include "tightfit/physics/autodiff.hpp"

namespace tightfit {

/// The regions resolved on one garment: which pieces each selects.
class PressureRegions {
 public:
  /// Throws InputError (source `source`) for an unnamed or duplicated region, a piece
  /// name the garment does not have (naming the region and the piece), a zero normal,
  /// a negative transition, or a non-finite or inverted range.
  /// `rig` (may be null when no region names bones) gives the skin weights, `radius`
  /// (m) their interpolation radius; a region naming bones without a rig, or a bone the
  /// rig does not have, is an InputError naming it.
  PressureRegions(const Garment& garment, std::vector<PressureRegion> regions,
                  const std::string& source, const SkinWeights* rig = nullptr,
                  double radius = 0.03);

  int size() const { return static_cast<int>(regions_.size()); }
  const PressureRegion& operator[](int r) const { return regions_[r]; }

  /// Regions whose pieces include triangle e's piece (candidates for a weight > 0).
  const std::vector<int>& candidates(int e) const { return candidates_[e]; }

  /// w of region r for a triangle with deformed corners `corners` (m); templated for
  /// automatic differentiation. Does not check the piece (see `candidates`).
  template <typename S>
  S band_weight(int r, const std::array<autodiff::Vec3T<S>, 3>& corners) const;

  /// w_{r,e} for every region r (rows) and garment triangle e (columns) at positions x
  /// (3·n_g, m).
  MatX weights(const VecX& x) const;

  /// Throws InputError (source `source`) naming every region whose weight is zero on
  /// every garment triangle at positions x: a region no garment covers.
  void check_covered(const VecX& x, const std::string& source) const;

 private:
  std::vector<PressureRegion> regions_;
  std::vector<std::vector<int>> candidates_;                    ///< per garment triangle
  std::vector<std::shared_ptr<const PointField>> bone_fields_;  ///< per region, null: no bones
  Triangles triangles_;                                         ///< garment triangles
};

namespace pressure_region_detail {

using autodiff::value_of;
using autodiff::Vec3T;

/// S(t): 0 for t <= −½, 1 for t >= ½, 3u² − 2u³ with u = t + ½ between.
template <typename S>
S smoothstep(const S& t) {
  if (value_of(t) <= -0.5) return S(0.0);
  if (value_of(t) >= 0.5) return S(1.0);
  const S u = t + 0.5;
  return u * u * (3.0 - 2.0 * u);
}

/// A scalar with value v and gradient g (w.r.t. the point c) as an S: the chain rule
/// through c's derivatives for automatic-differentiation scalars.
template <typename S>
S chain(double v, const Vec3& g, const Vec3T<S>& c) {
  if constexpr (std::is_same_v<S, double>) {
    return v;
  } else {
    S out(v);
    out.derivatives() =
        g.x() * c.x().derivatives() + g.y() * c.y().derivatives() + g.z() * c.z().derivatives();
    return out;
  }
}

/// Side weight of one plane: S(sign · d / δ), a hard step for δ = 0.
template <typename S>
S side_weight(const RegionPlane& plane, double sign, double transition, const Vec3T<S>& c) {
  const S d = sign * (c - plane.point.cast<S>()).dot(plane.normal.cast<S>());
  if (transition <= 0.0) return S(value_of(d) >= 0.0 ? 1.0 : 0.0);
  return smoothstep<S>(d / transition);
}

}  // namespace pressure_region_detail

template <typename S>
S PressureRegions::band_weight(int r, const std::array<autodiff::Vec3T<S>, 3>& corners) const {
  using namespace pressure_region_detail;
  const PressureRegion& region = regions_[r];
  const Vec3T<S> c = (corners[0] + corners[1] + corners[2]) / 3.0;
  S w(1.0);
  if (region.above) w = w * side_weight<S>(*region.above, 1.0, region.transition, c);
  if (region.below) w = w * side_weight<S>(*region.below, -1.0, region.transition, c);
  if (bone_fields_[r]) {
    Vec3 cv;
    for (int k = 0; k < 3; ++k) cv[k] = value_of(c[k]);
    const PointField::Evaluation b = bone_fields_[r]->evaluate(cv);
    w = w * chain<S>(b.value, b.gradient, c);
  }
  return w;
}

}  // namespace tightfit
