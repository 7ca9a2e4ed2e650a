#include "tightfit/objectives/element_kinematics.hpp"

#include <cmath>

#include <Eigen/LU>

#include "tightfit/common/error.hpp"

namespace tightfit {

ElementKinematics element_kinematics(const DesignState& state, const Triangles& triangles,
                                     const std::vector<int>& to_garment, Eigen::Index e,
                                     const std::string& source) {
  Mat2 dm;
  Mat32 ds;
  for (int k = 0; k < 2; ++k) {
    dm.col(k) = (state.rest.row(triangles(e, k + 1)) - state.rest.row(triangles(e, 0))).transpose();
    ds.col(k) = state.x.segment<3>(3 * to_garment[triangles(e, k + 1)]) -
                state.x.segment<3>(3 * to_garment[triangles(e, 0)]);
  }
  const double det = dm.determinant();
  if (!(std::abs(det) > 1e-14 * dm.squaredNorm()))
    throw SolverError(source + ": rest triangle " + std::to_string(e) + " is degenerate");
  ElementKinematics k;
  k.b = dm.inverse();
  k.f = ds * k.b;
  k.area = 0.5 * std::abs(det);
  k.c = k.f.transpose() * k.f;
  return k;
}

void add_element_gradient(const ElementKinematics& k, const Mat32& dT_dF, double density,
                          const Triangles& triangles, const std::vector<int>& to_garment,
                          Eigen::Index e, VecX& d_x, VecX& d_rest) {
  // F = Ds B: ∂/∂Ds = P Bᵀ; ∂/∂Dm = −Fᵀ P Bᵀ (through F) + s A Bᵀ (through A).
  const Mat32 g_ds = dT_dF * k.b.transpose();
  const Mat2 g_dm = -k.f.transpose() * dT_dF * k.b.transpose() + density * k.area * k.b.transpose();
  const int g0 = to_garment[triangles(e, 0)];
  const int p0 = triangles(e, 0);
  for (int j = 0; j < 2; ++j) {
    const int gj = to_garment[triangles(e, j + 1)];
    const int pj = triangles(e, j + 1);
    d_x.segment<3>(3 * gj) += g_ds.col(j);
    d_x.segment<3>(3 * g0) -= g_ds.col(j);
    d_rest.segment<2>(2 * pj) += g_dm.col(j);
    d_rest.segment<2>(2 * p0) -= g_dm.col(j);
  }
}

}  // namespace tightfit
