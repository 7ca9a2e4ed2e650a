#include "tightfit/objectives/posed_garment.hpp"

#include <stdexcept>

namespace tightfit {

PosedGarment pose_garment(const LimitSurface& surface, const DesignEmbedding& embedding,
                          const std::vector<PointMotion>& motions) {
  const int nc = surface.num_control_vertices();
  if (static_cast<int>(motions.size()) != embedding.body.rows() || embedding.body.rows() < nc)
    throw std::invalid_argument("pose_garment: one motion per body vertex expected");
  Points3 control(nc, 3);
  for (int k = 0; k < nc; ++k)
    control.row(k) =
        motions[static_cast<std::size_t>(k)].apply(embedding.body.row(k).transpose()).transpose();
  PosedGarment out;
  const int n = static_cast<int>(embedding.garment.size());
  out.x = VecX::Zero(3 * n);
  out.stencils.resize(static_cast<std::size_t>(n));
  for (Points3* m : {&out.xu, &out.xv, &out.xuu, &out.xuv, &out.xvv}) m->setZero(n, 3);
  for (int j = 0; j < n; ++j) {
    LimitWeights& w = out.stencils[static_cast<std::size_t>(j)];
    surface.weights(embedding.garment[static_cast<std::size_t>(j)], w);
    for (int k = 0; k < w.size(); ++k) {
      const auto y = control.row(w.index[k]);
      out.x.segment<3>(3 * j) += w.p[k] * y.transpose();
      out.xu.row(j) += w.du[k] * y;
      out.xv.row(j) += w.dv[k] * y;
      out.xuu.row(j) += w.duu[k] * y;
      out.xuv.row(j) += w.duv[k] * y;
      out.xvv.row(j) += w.dvv[k] * y;
    }
  }
  return out;
}

void add_posed_position_gradient(const PosedGarment& posed, const std::vector<PointMotion>& motions,
                                 const VecX& d_x, VecX& d_s, VecX& d_y) {
  const int n = static_cast<int>(posed.stencils.size());
  for (int j = 0; j < n; ++j) {
    const Vec3 g = d_x.segment<3>(3 * j);
    if (g.squaredNorm() == 0.0) continue;
    d_s[2 * j] += g.dot(posed.xu.row(j));
    d_s[2 * j + 1] += g.dot(posed.xv.row(j));
    const LimitWeights& st = posed.stencils[static_cast<std::size_t>(j)];
    for (int k = 0; k < st.size(); ++k)
      d_y.segment<3>(3 * st.index[k]) +=
          motions[static_cast<std::size_t>(st.index[k])].linear.transpose() * (st.p[k] * g);
  }
}

}  // namespace tightfit
