#include "tightfit/objectives/seam_traction_objective.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "tightfit/common/error.hpp"
#include "tightfit/physics/autodiff.hpp"

namespace tightfit {
namespace {

using namespace autodiff;  // NOLINT: the AD helper types

/// l0 · (S n·n) of one element for its seam edge (a, b): with d = X_b − X_a and
/// n = perp(d)/l0, l0 S n·n = perp(d)ᵀ S perp(d) / l0. `traction_only` drops the l0.
template <typename S>
S seam_term(const RelaxedStVK& law, const std::array<Vec3T<S>, 3>& x,
            const std::array<Vec2T<S>, 3>& r, int a, int b, bool traction_only) {
  using std::sqrt;
  Mat2T<S> dm;
  Mat32T<S> ds;
  for (int k = 0; k < 2; ++k) {
    dm.col(k) = r[k + 1] - r[0];
    ds.col(k) = x[k + 1] - x[0];
  }
  const Mat32T<S> f = ds * inverse2(dm);
  const Mat2T<S> c = f.transpose() * f;
  const Mat2T<S> stress = second_piola(law, c);
  const Vec2T<S> d = r[b] - r[a];
  Vec2T<S> n;
  n << -d(1), d(0);
  const S l0 = sqrt(d.squaredNorm());
  const S snn = n.dot(stress * n);
  return law.material().thickness * (traction_only ? S(snn / (l0 * l0)) : S(snn / l0));
}

}  // namespace

SeamTractionObjective::SeamTractionObjective(const Garment& garment, const ClothMaterial& material)
    : pattern_triangles_(garment.topology->pattern_triangles),
      pattern_to_garment_(garment.topology->pattern_to_garment),
      num_garment_(garment.num_garment_vertices()),
      num_pattern_(garment.num_pattern_vertices()),
      law_(material) {
  std::map<std::pair<int, int>, std::vector<int>> edge_triangles;
  for (int e = 0; e < static_cast<int>(pattern_triangles_.rows()); ++e)
    for (int k = 0; k < 3; ++k) {
      const int a = pattern_triangles_(e, k), b = pattern_triangles_(e, (k + 1) % 3);
      edge_triangles[{std::min(a, b), std::max(a, b)}].push_back(e);
    }
  for (const auto& [a, b] : garment.topology->seam_edges) {
    const auto it = edge_triangles.find({std::min(a, b), std::max(a, b)});
    if (it == edge_triangles.end())
      throw InputError("seam traction objective", "seam edge (" + std::to_string(a) + ", " +
                                                      std::to_string(b) +
                                                      ") is not an edge of any pattern triangle");
    for (int e : it->second) elements_.push_back({e, {a, b}});
  }
}

void SeamTractionObjective::check(const DesignState& state) const {
  if (state.x.size() != 3 * static_cast<Eigen::Index>(num_garment_) ||
      state.rest.rows() != num_pattern_)
    throw std::invalid_argument("seam traction objective: state has " +
                                std::to_string(state.x.size()) + " position entries and " +
                                std::to_string(state.rest.rows()) +
                                " rest positions, expected 3 x " + std::to_string(num_garment_) +
                                " and " + std::to_string(num_pattern_));
}

namespace {

/// Local corner index (0..2) of pattern vertex v in triangle e.
int corner_of(const Triangles& tri, int e, int v) {
  for (int k = 0; k < 3; ++k)
    if (tri(e, k) == v) return k;
  return -1;
}

}  // namespace

VecX SeamTractionObjective::tractions(const DesignState& state) const {
  check(state);
  VecX out(elements_.size());
  for (std::size_t i = 0; i < elements_.size(); ++i) {
    const SeamElement& el = elements_[i];
    std::array<Vec3, 3> x;
    std::array<Vec2, 3> r;
    for (int k = 0; k < 3; ++k) {
      x[k] = state.x.segment<3>(3 * pattern_to_garment_[pattern_triangles_(el.triangle, k)]);
      r[k] = state.rest.row(pattern_triangles_(el.triangle, k)).transpose();
    }
    out[static_cast<Eigen::Index>(i)] =
        seam_term<double>(law_, x, r, corner_of(pattern_triangles_, el.triangle, el.edge[0]),
                          corner_of(pattern_triangles_, el.triangle, el.edge[1]), true);
  }
  return out;
}

double SeamTractionObjective::value(const DesignState& state) const {
  check(state);
  double total = 0.0;
  for (const SeamElement& el : elements_) {
    std::array<Vec3, 3> x;
    std::array<Vec2, 3> r;
    for (int k = 0; k < 3; ++k) {
      x[k] = state.x.segment<3>(3 * pattern_to_garment_[pattern_triangles_(el.triangle, k)]);
      r[k] = state.rest.row(pattern_triangles_(el.triangle, k)).transpose();
    }
    total += seam_term<double>(law_, x, r, corner_of(pattern_triangles_, el.triangle, el.edge[0]),
                               corner_of(pattern_triangles_, el.triangle, el.edge[1]), false);
  }
  return total;
}

void SeamTractionObjective::add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const {
  check(state);
  if (d_x.size() != state.x.size() || d_rest.size() != 2 * state.rest.rows())
    throw std::invalid_argument("seam traction objective: gradient vectors have the wrong size");
  constexpr int kN = 15;  // 9 positions, 6 rest coordinates
  using S = Scalar<kN>;
  for (const SeamElement& el : elements_) {
    std::array<Vec3T<S>, 3> x;
    std::array<Vec2T<S>, 3> r;
    for (int k = 0; k < 3; ++k) {
      const int pv = pattern_triangles_(el.triangle, k);
      const int gv = pattern_to_garment_[pv];
      for (int c = 0; c < 3; ++c) x[k](c) = variable<kN>(state.x[3 * gv + c], 3 * k + c);
      for (int c = 0; c < 2; ++c) r[k](c) = variable<kN>(state.rest(pv, c), 9 + 2 * k + c);
    }
    const S t = seam_term<S>(law_, x, r, corner_of(pattern_triangles_, el.triangle, el.edge[0]),
                             corner_of(pattern_triangles_, el.triangle, el.edge[1]), false);
    const Eigen::Matrix<double, kN, 1>& g = t.derivatives();
    for (int k = 0; k < 3; ++k) {
      const int pv = pattern_triangles_(el.triangle, k);
      d_x.segment<3>(3 * pattern_to_garment_[pv]) += g.segment<3>(3 * k);
      d_rest.segment<2>(2 * pv) += g.segment<2>(9 + 2 * k);
    }
  }
}

}  // namespace tightfit
