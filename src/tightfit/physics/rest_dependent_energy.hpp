#pragma once
/// An energy U(x, Xbar) that also depends on the 2D rest positions Xbar of the pattern
/// vertices (cloth and seam springs). Xbar is n_p×2 (m); as a flat vector its DOF index
/// is 2·p + k. These derivatives feed the adjoint design gradient (docs/design.md §4:
/// ∂g/∂p = (∂²U/∂q∂Xbar) W).
///
/// The energy does not own Xbar: it reads the array it is bound to on every call, as
/// ipc-toolkit's potentials read the rest positions they are passed. A simulation binds
/// its energies to its ONE rest array (GarmentSimulation), so a design step that writes
/// that array moves every energy at once; a design term binds energies to the rest of
/// the design state it evaluates. The bound array must outlive the binding; binding to
/// a temporary does not compile.
#include <vector>

#include "tightfit/physics/energy.hpp"

namespace tightfit {

class RestDependentEnergy : public Energy {
 public:
  /// Number of pattern vertices n_p (rows of Xbar).
  int num_pattern_vertices() const { return static_cast<int>(rest_->rows()); }
  /// The rest positions Xbar the energy reads (n_p×2, m).
  const Points2& rest() const { return *rest_; }
  /// Reads Xbar from `rest` (same n_p) from now on. Throws InputError, and keeps the
  /// previous binding, when `rest` has the wrong size or makes an element degenerate.
  void bind_rest(const Points2& rest) {
    check_rest(rest);
    rest_ = &rest;
  }
  void bind_rest(const Points2&&) = delete;
  /// Throws InputError when `rest` (n_p×2) does not fit this energy: wrong row count, or
  /// an element with zero rest area or length.
  virtual void check_rest(const Points2& rest) const = 0;
  /// g_rest += ∂U/∂Xbar (J/m, length 2·n_p) at positions x.
  virtual void add_gradient_rest(const VecX& x, VecX& g_rest) const = 0;
  /// Adds ∂²U/∂x∂Xbar (N/m) as triplets: rows index x (3·n_garment), columns index
  /// Xbar (2·n_p).
  virtual void add_mixed_rest(const VecX& x, std::vector<Triplet>& H) const = 0;

 protected:
  /// Binds `rest` without checking it: the derived constructor checks it (check_rest is
  /// virtual, so the base cannot).
  explicit RestDependentEnergy(const Points2& rest) : rest_(&rest) {}

 private:
  const Points2* rest_;
};

}  // namespace tightfit
