#pragma once
/// Design terms and checks shared by the remeshing tests (tests/design/
/// pattern_remesh_test.cpp, tests/scene/remesh_checkpoint_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "tightfit/design/optimization_state.hpp"
#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"

namespace tightfit::test {

/// Pulls the vertices of the pinned boundary `ring` of the pattern towards the curve
/// y = top − depth sin²(π x / width): the top edge of the sleeve piece dips in its
/// middle, squashing the triangles below it. T = ½ Σ (y_v − g(x_v))² (m²), Xbar only.
class DipTerm : public DesignTerm {
 public:
  DipTerm(const Garment& g, const std::string& ring, double top, double depth, double width)
      : top_(top), depth_(depth), width_(width) {
    for (const PinnedBoundary& pin : g.pattern.pinned)
      if (pin.name == ring)
        for (int v : pin.vertices) vertices_.push_back(g.topology->piece_offset[pin.piece] + v);
    if (vertices_.empty()) throw std::invalid_argument("DipTerm: no such ring");
  }
  std::string name() const override { return "dip"; }
  double value(const DesignState& s) const override {
    double t = 0.0;
    for (int v : vertices_) t += 0.5 * std::pow(residual(s, v), 2);
    return t;
  }
  void add_gradient(const DesignState& s, VecX&, VecX& d_rest) const override {
    const double k = std::numbers::pi / width_;
    for (int v : vertices_) {
      const double r = residual(s, v);
      const double slope = -depth_ * k * std::sin(2.0 * k * s.rest(v, 0));  // g'(x)
      d_rest[2 * v] += -r * slope;
      d_rest[2 * v + 1] += r;
    }
  }
  bool depends_on_positions() const override { return false; }

 private:
  double residual(const DesignState& s, int v) const {
    const double sn = std::sin(std::numbers::pi * s.rest(v, 0) / width_);
    return s.rest(v, 1) - (top_ - depth_ * sn * sn);
  }
  std::vector<int> vertices_;
  double top_, depth_, width_;
};

/// Accepted values decrease; across a remeshing the next value is compared with the
/// remeshed pattern's value.
inline void expect_monotone_across_remeshes(const std::vector<OptimizationIteration>& h) {
  for (size_t k = 1; k < h.size(); ++k) {
    const double before = h[k - 1].remesh && h[k - 1].remesh->failure.empty()
                              ? h[k - 1].remesh->value
                              : h[k - 1].value;
    EXPECT_LT(h[k].value, before) << "iteration " << h[k].iteration;
  }
}

}  // namespace tightfit::test
