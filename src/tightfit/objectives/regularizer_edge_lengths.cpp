#include "tightfit/objectives/regularizer_edge_lengths.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "tightfit/objectives/rest_term_checks.hpp"

namespace tightfit {
namespace {

double edge_length(const Points2& rest, const std::array<int, 2>& e) {
  return (rest.row(e[1]) - rest.row(e[0])).norm();
}

/// d_rest += c · ∂‖e‖/∂Xbar.
void add_edge_length_gradient(const Points2& rest, const std::array<int, 2>& e, double c,
                              VecX& d_rest) {
  const Vec2 d = (rest.row(e[1]) - rest.row(e[0])).transpose();
  const Vec2 g = c * d / d.norm();
  d_rest.segment<2>(2 * e[1]) += g;
  d_rest.segment<2>(2 * e[0]) -= g;
}

}  // namespace

EdgeLengthDifferenceTerm::EdgeLengthDifferenceTerm(std::string name, std::vector<EdgePair> pairs,
                                                   int num_pattern_vertices)
    : name_(std::move(name)), pairs_(std::move(pairs)), num_pattern_(num_pattern_vertices) {
  for (const EdgePair& p : pairs_) {
    for (int v : {p.first[0], p.first[1], p.second[0], p.second[1]})
      if (v < 0 || v >= num_pattern_)
        throw std::invalid_argument(name_ + ": pattern vertex " + std::to_string(v) +
                                    " outside [0, " + std::to_string(num_pattern_) + ")");
    if (!std::isfinite(p.weight) || p.weight < 0.0)
      throw std::invalid_argument(name_ + ": a pair weight is negative or not finite");
  }
}

double EdgeLengthDifferenceTerm::value(const DesignState& state) const {
  check_rest_rows(name_, state.rest, num_pattern_);
  double total = 0.0;
  for (const EdgePair& p : pairs_) {
    const double diff = edge_length(state.rest, p.first) - edge_length(state.rest, p.second);
    total += p.weight * diff * diff;
  }
  return total;
}

void EdgeLengthDifferenceTerm::add_gradient(const DesignState& state, VecX& /*d_x*/,
                                            VecX& d_rest) const {
  check_rest_rows(name_, state.rest, num_pattern_);
  check_rest_gradient_size(name_, d_rest, num_pattern_);
  for (const EdgePair& p : pairs_) {
    const double diff = edge_length(state.rest, p.first) - edge_length(state.rest, p.second);
    add_edge_length_gradient(state.rest, p.first, 2.0 * p.weight * diff, d_rest);
    add_edge_length_gradient(state.rest, p.second, -2.0 * p.weight * diff, d_rest);
  }
}

namespace {

/// Sets every pair's weight: `reference`'s boundary edge (the garment's own when not
/// known) over the mean rest length of the pair's two edges.
void weigh_pairs(std::vector<EdgeLengthDifferenceTerm::EdgePair>& pairs, const Garment& garment,
                 const ResolutionReference& reference) {
  const double edge = resolution_or_own(reference, garment).boundary_edge;
  const Points2 rest = garment.rest_positions();
  for (EdgeLengthDifferenceTerm::EdgePair& p : pairs) {
    const double mean = 0.5 * (edge_length(rest, p.first) + edge_length(rest, p.second));
    p.weight = mean > 0.0 ? edge / mean : 1.0;
  }
}

}  // namespace

EdgeLengthDifferenceTerm seam_length_regularizer(const Garment& garment,
                                                 const ResolutionReference& reference) {
  std::vector<EdgeLengthDifferenceTerm::EdgePair> pairs;
  for (const Seam& seam : garment.pattern.seams) {
    const int oa = garment.topology->piece_offset.at(seam.a.piece);
    const int ob = garment.topology->piece_offset.at(seam.b.piece);
    const std::size_t k = std::min(seam.a.vertices.size(), seam.b.vertices.size());
    for (std::size_t i = 0; i + 1 < k; ++i)
      pairs.push_back({{oa + seam.a.vertices[i], oa + seam.a.vertices[i + 1]},
                       {ob + seam.b.vertices[i], ob + seam.b.vertices[i + 1]}});
  }
  weigh_pairs(pairs, garment, reference);
  return EdgeLengthDifferenceTerm("seam length", std::move(pairs), garment.num_pattern_vertices());
}

EdgeLengthDifferenceTerm even_spacing_regularizer(const Garment& garment,
                                                  const ResolutionReference& reference) {
  std::vector<EdgeLengthDifferenceTerm::EdgePair> pairs;
  for (std::size_t k = 0; k < garment.pattern.pieces.size(); ++k) {
    const int o = garment.topology->piece_offset[k];
    for (const std::vector<int>& loop : garment.pattern.pieces[k].loops()) {
      const std::size_t n = loop.size();
      if (n < 3) continue;
      for (std::size_t i = 0; i < n; ++i) {
        const int prev = o + loop[(i + n - 1) % n], v = o + loop[i], next = o + loop[(i + 1) % n];
        pairs.push_back({{prev, v}, {v, next}});
      }
    }
  }
  weigh_pairs(pairs, garment, reference);
  return EdgeLengthDifferenceTerm("boundary spacing", std::move(pairs),
                                  garment.num_pattern_vertices());
}

}  // namespace tightfit
