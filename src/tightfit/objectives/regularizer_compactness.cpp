#include "tightfit/objectives/regularizer_compactness.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "tightfit/objectives/rest_term_checks.hpp"

namespace tightfit {
namespace {

/// Edge lengths of a loop (edge k joins positions k and k+1) and their prefix sums.
struct LoopLengths {
  VecX length;  // n
  VecX prefix;  // n+1, prefix[k] = Σ_{m<k} length[m]
};

LoopLengths loop_lengths(const Points2& rest, const std::vector<int>& loop) {
  const int n = static_cast<int>(loop.size());
  LoopLengths l{VecX(n), VecX(n + 1)};
  l.prefix[0] = 0.0;
  for (int k = 0; k < n; ++k) {
    l.length[k] = (rest.row(loop[(k + 1) % n]) - rest.row(loop[k])).norm();
    l.prefix[k + 1] = l.prefix[k] + l.length[k];
  }
  return l;
}

double path_length(const LoopLengths& l, int start, int count) {
  const int n = static_cast<int>(l.length.size());
  const int end = start + count;
  if (end <= n) return l.prefix[end] - l.prefix[start];
  return l.prefix[n] - l.prefix[start] + l.prefix[end - n];
}

}  // namespace

CompactnessRegularizer::CompactnessRegularizer(const Garment& garment, CompactnessOptions options,
                                               const ResolutionReference& reference)
    : options_(options), num_pattern_(garment.num_pattern_vertices()) {
  if (!(options_.min_ratio > 0.0 && options_.min_ratio <= 1.0))
    throw std::invalid_argument("compactness: r_D must lie in (0, 1]");
  if (options_.pair_stride < 1)
    throw std::invalid_argument("compactness: pair stride must be >= 1");
  const Points2 rest = garment.rest_positions();
  const double reference_edge = resolution_or_own(reference, garment).boundary_edge;
  for (std::size_t k = 0; k < garment.pattern.pieces.size(); ++k)
    for (const std::vector<int>& piece_loop : garment.pattern.pieces[k].loops()) {
      Loop loop;
      const int o = garment.topology->piece_offset[k];
      for (int v : piece_loop) loop.vertices.push_back(o + v);
      const int n = static_cast<int>(loop.vertices.size());
      if (n < 4) continue;
      const LoopLengths l = loop_lengths(rest, loop.vertices);
      const int s = options_.pair_stride;
      // A pair stands for the boundary around its two ends (a loop of n vertices has ~n²
      // pairs): w = σ_i σ_j / h², σ the share of boundary length of an end (s edges).
      auto share = [&](int i) {
        return 0.5 * s * (l.length[i] + l.length[(i + n - 1) % n]) / reference_edge;
      };
      for (int i = 0; i < n; i += s)
        for (int j = i + s; j < n; j += s) {
          const int forward = j - i, backward = n - forward;
          const bool use_forward =
              l.prefix[j] - l.prefix[i] <= l.prefix[n] - (l.prefix[j] - l.prefix[i]);
          Pair p{i, j, use_forward ? i : j, use_forward ? forward : backward,
                 reference_edge > 0.0 ? share(i) * share(j) : 1.0};
          if (p.count >= 2) loop.pairs.push_back(p);
        }
      loops_.push_back(std::move(loop));
    }
}

std::vector<double> CompactnessRegularizer::ratios(const Points2& rest) const {
  std::vector<double> out;
  for (const Loop& loop : loops_) {
    const LoopLengths l = loop_lengths(rest, loop.vertices);
    for (const Pair& p : loop.pairs)
      out.push_back((rest.row(loop.vertices[p.i]) - rest.row(loop.vertices[p.j])).norm() /
                    path_length(l, p.start, p.count));
  }
  return out;
}

double CompactnessRegularizer::value(const DesignState& state) const {
  check_rest_rows(name(), state.rest, num_pattern_);
  const double rd = options_.min_ratio;
  double total = 0.0;
  for (const Loop& loop : loops_) {
    const LoopLengths l = loop_lengths(state.rest, loop.vertices);
    for (const Pair& p : loop.pairs) {
      const double rho =
          (state.rest.row(loop.vertices[p.i]) - state.rest.row(loop.vertices[p.j])).norm() /
          path_length(l, p.start, p.count);
      if (rho < rd) total += p.weight * std::pow(rho - rd, 4);
    }
  }
  return total;
}

void CompactnessRegularizer::add_gradient(const DesignState& state, VecX& /*d_x*/,
                                          VecX& d_rest) const {
  check_rest_rows(name(), state.rest, num_pattern_);
  check_rest_gradient_size(name(), d_rest, num_pattern_);
  const double rd = options_.min_ratio;
  const Points2& rest = state.rest;
  for (const Loop& loop : loops_) {
    const int n = static_cast<int>(loop.vertices.size());
    const LoopLengths l = loop_lengths(rest, loop.vertices);
    // ∂R/∂(path length) accumulated on the path's edges through a cyclic difference array.
    VecX diff = VecX::Zero(n + 1);
    for (const Pair& p : loop.pairs) {
      const int vi = loop.vertices[p.i], vj = loop.vertices[p.j];
      const Vec2 d = (rest.row(vi) - rest.row(vj)).transpose();
      const double dist = d.norm();
      const double len = path_length(l, p.start, p.count);
      const double rho = dist / len;
      if (!(rho < rd)) continue;
      const double dr = 4.0 * p.weight * std::pow(rho - rd, 3);  // dR/dρ
      // ρ = dist/len: ∂ρ/∂dist = 1/len, ∂ρ/∂len = −ρ/len.
      const Vec2 g = dr / len * d / dist;
      d_rest.segment<2>(2 * vi) += g;
      d_rest.segment<2>(2 * vj) -= g;
      const double c = -dr * rho / len;
      const int end = p.start + p.count;
      diff[p.start] += c;
      if (end <= n) {
        diff[end] -= c;
      } else {
        diff[n] -= c;
        diff[0] += c;
        diff[end - n] -= c;
      }
    }
    double coeff = 0.0;
    for (int k = 0; k < n; ++k) {
      coeff += diff[k];
      if (coeff == 0.0) continue;
      const int a = loop.vertices[k], b = loop.vertices[(k + 1) % n];
      const Vec2 e = (rest.row(b) - rest.row(a)).transpose();
      const Vec2 g = coeff * e / l.length[k];
      d_rest.segment<2>(2 * b) += g;
      d_rest.segment<2>(2 * a) -= g;
    }
  }
}

}  // namespace tightfit
