#pragma once
/// The energy interface of the physics layer. An energy U(x) is a function of a flat
/// vector of 3D positions x = (x0, y0, z0, x1, y1, z1, ...) in metres, U in joules.
/// Implementations evaluate per element (a local value, gradient and Hessian over the
/// element's vertices) and scatter into global arrays (see assembly.hpp), in the style
/// of ipc-toolkit.
#include <string>
#include <vector>

#include "tightfit/common/element_matrices.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

class Energy {
 public:
  virtual ~Energy() = default;

  /// Short human-readable name ("neo-hookean", "cloth", ...), for logs and reports.
  virtual std::string name() const = 0;

  /// U(x) in J. +infinity marks an inadmissible state (e.g. an inverted tetrahedron);
  /// a line search rejects such states.
  virtual double value(const VecX& x) const = 0;

  /// g += dU/dx (N, same length as x).
  virtual void add_gradient(const VecX& x, VecX& g) const = 0;

  /// H += d²U/dx² (N/m) as triplets with row/column indices into x (duplicates are
  /// summed on assembly). Both triangles are written. With `project_psd`, each element's
  /// local Hessian is first projected onto the positive semi-definite cone (negative
  /// eigenvalues clamped to zero), which keeps Newton steps descent directions.
  virtual void add_hessian(const VecX& x, std::vector<Triplet>& H,
                           bool project_psd = false) const = 0;
  /// The same Hessian as add_hessian, element by element: appends one ElementMatrices
  /// (the element matrices over vertices of x, 3 DOFs each; their sum is d²U/dx²) and
  /// returns true, or returns false without appending when the energy is not such a
  /// sum (the caller then uses add_hessian). Assembling element matrices
  /// (BlockSparseMatrix3::assemble) moves a ninth of the memory that triplets do.
  virtual bool add_element_hessians(const VecX& x, std::vector<ElementMatrices>& H,
                                    bool project_psd = false) const {
    (void)x;
    (void)H;
    (void)project_psd;
    return false;
  }
};

}  // namespace tightfit
