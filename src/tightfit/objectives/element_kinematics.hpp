#pragma once
/// Per-triangle kinematics shared by the objectives that are integrals over the pattern
/// of a function of the deformation gradient (stretch, directional stretch):
/// T_e = A_e s(F_e), with F = Ds Dm⁻¹ (Ds: 3×2 deformed edges, m; Dm: 2×2 rest edges, m)
/// and A_e the rest area (m²).
#include <string>
#include <vector>

#include "tightfit/objectives/design_term.hpp"

namespace tightfit {

/// The element's F (3×2), its rest-edge inverse B = Dm⁻¹ (1/m), rest area (m²) and
/// C = FᵀF (2×2).
struct ElementKinematics {
  Mat32 f;
  Mat2 b;
  double area = 0.0;
  Mat2 c;
};

/// Kinematics of pattern triangle `e` (global pattern-vertex indices in `triangles`,
/// garment vertex of each pattern vertex in `to_garment`). Throws SolverError naming
/// `source` if the rest triangle is degenerate.
ElementKinematics element_kinematics(const DesignState& state, const Triangles& triangles,
                                     const std::vector<int>& to_garment, Eigen::Index e,
                                     const std::string& source);

/// Adds the gradient of T_e = A_e s(F) to d_x (3·n_garment) and d_rest (2·n_pattern),
/// given s (`density`) and ∂T_e/∂F = A_e ∂s/∂F (`dT_dF`, 3×2): through F = Ds B on the
/// deformed positions, and through F and A_e on the rest positions.
void add_element_gradient(const ElementKinematics& k, const Mat32& dT_dF, double density,
                          const Triangles& triangles, const std::vector<int>& to_garment,
                          Eigen::Index e, VecX& d_x, VecX& d_rest);

}  // namespace tightfit
