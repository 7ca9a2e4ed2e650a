#include "tightfit/objectives/shape_objective.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace tightfit {

ShapeObjective::ShapeObjective(ImlsSurface target, int num_garment_vertices,
                               std::vector<int> vertices, VecX weights)
    : target_(std::move(target)),
      num_garment_(num_garment_vertices),
      vertices_(std::move(vertices)),
      weights_(std::move(weights)) {
  if (weights_.size() == 0) weights_ = VecX::Ones(num_garment_);
  if (weights_.size() != num_garment_ || !weights_.allFinite() || weights_.minCoeff() < 0.0)
    throw std::invalid_argument("shape objective: expected " + std::to_string(num_garment_) +
                                " finite, non-negative vertex weights");
  if (vertices_.empty()) {
    vertices_.resize(num_garment_);
    std::iota(vertices_.begin(), vertices_.end(), 0);
  }
  for (int v : vertices_)
    if (v < 0 || v >= num_garment_)
      throw std::invalid_argument("shape objective: garment vertex " + std::to_string(v) +
                                  " outside [0, " + std::to_string(num_garment_) + ")");
}

void ShapeObjective::check(const VecX& x) const {
  if (x.size() != 3 * static_cast<Eigen::Index>(num_garment_))
    throw std::invalid_argument("shape objective: position vector has " + std::to_string(x.size()) +
                                " entries, expected 3 x " + std::to_string(num_garment_));
}

VecX ShapeObjective::distances(const VecX& x) const {
  check(x);
  VecX f(vertices_.size());
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    f[static_cast<Eigen::Index>(i)] = target_.evaluate(x.segment<3>(3 * vertices_[i])).value;
  return f;
}

double ShapeObjective::value(const DesignState& state) const {
  const VecX f = distances(state.x);
  double total = 0.0;
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    total +=
        weights_[vertices_[i]] * f[static_cast<Eigen::Index>(i)] * f[static_cast<Eigen::Index>(i)];
  return total;
}

void ShapeObjective::add_gradient(const DesignState& state, VecX& d_x, VecX& /*d_rest*/) const {
  check(state.x);
  if (d_x.size() != state.x.size())
    throw std::invalid_argument("shape objective: position gradient has the wrong size");
  for (int v : vertices_) {
    const ImlsSurface::Evaluation ev = target_.evaluate(state.x.segment<3>(3 * v));
    d_x.segment<3>(3 * v) += 2.0 * weights_[v] * ev.value * ev.gradient;
  }
}

VecX shape_vertex_weights(const Garment& garment, const ResolutionReference& reference) {
  return garment_vertex_areas(garment) / resolution_or_own(reference, garment).vertex_area;
}

std::vector<int> unpinned_vertices(const Garment& garment) {
  std::vector<int> out;
  for (int v = 0; v < garment.num_garment_vertices(); ++v)
    if (!std::binary_search(garment.topology->pinned.begin(), garment.topology->pinned.end(), v))
      out.push_back(v);
  return out;
}

}  // namespace tightfit
