#pragma once
/// The one interface of everything the pattern optimizer minimizes: design objectives
/// (paper Sec. 5: stretch, shape, pressure, seam traction) and regularizers (Sec. 4.1:
/// seam length, boundary smoothness, even spacing, compactness).
///
/// A term T(x, Xbar) is a function of
///  * x:    the garment positions at equilibrium, 3·n_g (m), one 3D point per WELDED
///          garment vertex (Garment::pattern_to_garment), flat (x0, y0, z0, x1, ...);
///  * Xbar: the 2D rest positions of all pattern vertices, n_p×2 (m), stacked piece
///          after piece (Garment::piece_offset); as a flat vector its DOF is 2·v + k.
/// The adjoint gradient (docs/design.md §4, Eq. 23) needs ∂T/∂x and ∂T/∂Xbar; the chain to
/// the design parameters p goes through the biharmonic coordinates, ∂T/∂p = Wᵀ ∂T/∂Xbar
/// (biharmonic_coordinates.hpp).
///
/// Weights. Terms are UNWEIGHTED: each evaluates the paper's formula in its own units
/// (documented per term). The scene's weights live outside, in DesignTermSum, which is
/// itself a DesignTerm (T = Σ w_j T_j), so the optimizer sees one term.
///
/// Remeshing. Terms hold index sets of one pattern/garment topology (triangles,
/// boundary loops, seams) and are rebuilt when the patterns are remeshed.
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/subdiv/surface_point.hpp"

namespace tightfit {

/// The embedded state the garment positions come from (solve/embedded_equilibrium.hpp):
/// garment vertex i at surface point garment[i] of the body's limit surface, the body at
/// `body` (n_b×3, m). Terms that look at the garment in other body poses (the sliding
/// objective) need it; x alone does not determine them.
struct DesignEmbedding {
  const std::vector<SurfacePoint>& garment;
  const Points3& body;
};

/// The state a design term is evaluated at. Holds references: keep x and rest alive.
struct DesignState {
  const VecX& x;        ///< garment positions, 3·n_g (m)
  const Points2& rest;  ///< pattern rest positions Xbar, n_p×2 (m)
  /// The embedded state behind x; null where the caller has none (terms that need it
  /// throw std::logic_error then).
  const DesignEmbedding* embedding = nullptr;
};

class DesignTerm {
 public:
  virtual ~DesignTerm() = default;

  /// Short name for logs and reports ("stretch", "seam length", ...).
  virtual std::string name() const = 0;

  /// T(x, Xbar) in the term's own units (see the term's header).
  virtual double value(const DesignState& state) const = 0;

  /// d_x += ∂T/∂x (length 3·n_g) and d_rest += ∂T/∂Xbar (length 2·n_p). Both vectors
  /// must already have these sizes; terms add only what they depend on.
  virtual void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const = 0;

  /// False when T depends neither on x nor on the embedded state (the regularizers): it
  /// needs no adjoint solve.
  virtual bool depends_on_positions() const = 0;

  /// True when T depends on the embedded state itself, not only through x.
  virtual bool depends_on_embedding() const { return false; }
  /// d_s += ∂T/∂s (2·n_g: per garment vertex, its (u, v) in its current face) and
  /// d_y += ∂T/∂y (3·n_b) at fixed x and Xbar; sizes as given. Only for terms that
  /// depend_on_embedding(); the state must carry the embedding.
  virtual void add_embedding_gradient(const DesignState& state, VecX& d_s, VecX& d_y) const {}
};

/// A weighted sum T = Σ_j w_j T_j of design terms (the scene's objective). Weights are
/// finite and >= 0; a term of weight 0 is skipped entirely.
class DesignTermSum : public DesignTerm {
 public:
  struct Entry {
    std::shared_ptr<const DesignTerm> term;
    double weight = 1.0;
  };

  /// Adds a term. Throws std::invalid_argument for a null term or a negative or
  /// non-finite weight.
  void add(std::shared_ptr<const DesignTerm> term, double weight) {
    if (!term) throw std::invalid_argument("DesignTermSum::add: null term");
    if (!std::isfinite(weight) || weight < 0.0)
      throw std::invalid_argument("DesignTermSum::add: weight of '" + term->name() +
                                  "' must be finite and >= 0");
    entries_.push_back({std::move(term), weight});
  }

  const std::vector<Entry>& entries() const { return entries_; }

  std::string name() const override { return "design objective"; }

  double value(const DesignState& state) const override {
    double total = 0.0;
    for (const Entry& e : entries_)
      if (e.weight > 0.0) total += e.weight * e.term->value(state);
    return total;
  }

  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override {
    VecX gx(d_x.size());
    VecX gr(d_rest.size());
    for (const Entry& e : entries_) {
      if (e.weight == 0.0) continue;
      gx.setZero();
      gr.setZero();
      e.term->add_gradient(state, gx, gr);
      d_x += e.weight * gx;
      d_rest += e.weight * gr;
    }
  }

  bool depends_on_positions() const override {
    for (const Entry& e : entries_)
      if (e.weight > 0.0 && e.term->depends_on_positions()) return true;
    return false;
  }

  bool depends_on_embedding() const override {
    for (const Entry& e : entries_)
      if (e.weight > 0.0 && e.term->depends_on_embedding()) return true;
    return false;
  }

  void add_embedding_gradient(const DesignState& state, VecX& d_s, VecX& d_y) const override {
    VecX gs(d_s.size());
    VecX gy(d_y.size());
    for (const Entry& e : entries_) {
      if (e.weight == 0.0 || !e.term->depends_on_embedding()) continue;
      gs.setZero();
      gy.setZero();
      e.term->add_embedding_gradient(state, gs, gy);
      d_s += e.weight * gs;
      d_y += e.weight * gy;
    }
  }

  /// Weighted value w_j T_j of every entry, in entry order (0 for weight 0), for logs.
  std::vector<double> weighted_values(const DesignState& state) const {
    std::vector<double> out;
    out.reserve(entries_.size());
    for (const Entry& e : entries_)
      out.push_back(e.weight > 0.0 ? e.weight * e.term->value(state) : 0.0);
    return out;
  }

 private:
  std::vector<Entry> entries_;
};

/// Names of the objective's entries for records and logs: the term names, made unique
/// by appending " 2", " 3", ... to repeated ones.
inline std::vector<std::string> term_names(const DesignTermSum& objective) {
  std::vector<std::string> names;
  for (const DesignTermSum::Entry& e : objective.entries()) {
    const std::string base = e.term->name();
    std::string name = base;
    for (int k = 2; std::find(names.begin(), names.end(), name) != names.end(); ++k)
      name = base + " " + std::to_string(k);
    names.push_back(name);
  }
  return names;
}

}  // namespace tightfit
