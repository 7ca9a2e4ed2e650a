#include "tightfit/objectives/sliding_objective.hpp"

#include <cmath>
#include <stdexcept>

#include "tightfit/common/error.hpp"

namespace tightfit {

/// One pose evaluated at a state: posed positions and frames, forces, and (with the
/// gradient) a = ∂T/∂f (3·n_g) and ∂T/∂n per vertex.
struct SlidingObjective::PoseEvaluation {
  double value = 0.0;
  SlidingForces forces;
  PosedGarment posed;
  VecX a;
  Points3 gn;
};

SlidingObjective::SlidingObjective(const Garment& garment, const SimulationMaterials& materials,
                                   const LimitSurface& surface, int num_body_vertices,
                                   std::vector<PoseMotions> poses, double friction, VecX weights)
    : surface_(surface),
      num_garment_(garment.num_garment_vertices()),
      num_body_(num_body_vertices),
      pinned_(static_cast<std::size_t>(garment.num_garment_vertices()), 0),
      poses_(std::move(poses)),
      friction_(friction),
      topology_(garment.topology),
      fabric_(materials.fabric),
      seam_(materials.seam),
      weights_(std::move(weights)) {
  const std::string source = "sliding objective";
  if (weights_.size() == 0) weights_ = VecX::Ones(num_garment_);
  if (weights_.size() != num_garment_ || !weights_.allFinite() || weights_.minCoeff() < 0.0)
    throw std::invalid_argument("SlidingObjective: expected " + std::to_string(num_garment_) +
                                " finite, non-negative vertex weights");
  if (!std::isfinite(friction) || friction < 0.0)
    throw InputError(source, "the friction coefficient must be finite and >= 0");
  if (poses_.empty()) throw InputError(source, "no poses to evaluate");
  for (const PoseMotions& p : poses_)
    if (static_cast<int>(p.motions.size()) != num_body_vertices)
      throw InputError(
          source, "pose \"" + p.name + "\" has motions for " + std::to_string(p.motions.size()) +
                      " body vertices, the body has " + std::to_string(num_body_vertices));
  if (num_body_vertices < surface.num_control_vertices())
    throw InputError(source, "the body has fewer vertices than its surface");
  for (int v : garment.topology->pinned) pinned_[static_cast<std::size_t>(v)] = 1;
}

SlidingObjective::~SlidingObjective() = default;

GarmentEnergies SlidingObjective::energies_at(const Points2& rest) const {
  return GarmentEnergies(topology_, rest, fabric_, seam_);
}

SlidingObjective::PoseEvaluation SlidingObjective::evaluate(const DesignState& state,
                                                            const GarmentEnergies& energies,
                                                            int pose, bool with_gradient) const {
  if (state.embedding == nullptr)
    throw std::logic_error("SlidingObjective: the design state carries no embedding");
  const DesignEmbedding& emb = *state.embedding;
  if (static_cast<int>(emb.garment.size()) != num_garment_ || emb.body.rows() != num_body_)
    throw std::invalid_argument(
        "SlidingObjective: the embedding does not match the garment and body");
  PoseEvaluation ev;
  ev.posed = pose_garment(surface_, emb, poses_[static_cast<std::size_t>(pose)].motions);
  const PosedGarment& pg = ev.posed;
  const int n = num_garment_;
  VecX g = VecX::Zero(3 * n);
  for (const RestDependentEnergy* e : energies.all()) e->add_gradient(pg.x, g);
  ev.forces.normal = VecX::Zero(n);
  ev.forces.tangential = VecX::Zero(n);
  ev.forces.excess = VecX::Zero(n);
  if (with_gradient) {
    ev.a = VecX::Zero(3 * n);
    ev.gn = Points3::Zero(n, 3);
  }
  for (int j = 0; j < n; ++j) {
    const Vec3 f = -g.segment<3>(3 * j);
    const Vec3 normal = Vec3(pg.xu.row(j)).cross(Vec3(pg.xv.row(j))).normalized();
    const double fr = f.dot(normal);  // the pressing force is −fr (n points outward)
    const Vec3 ft_vec = f - fr * normal;
    const double ft = ft_vec.norm();
    ev.forces.normal[j] = -fr;
    ev.forces.tangential[j] = ft;
    if (pinned_[static_cast<std::size_t>(j)]) continue;
    const bool pressing = fr < 0.0;
    const double excess = ft - friction_ * (pressing ? -fr : 0.0);
    if (!(excess > 0.0)) continue;
    ev.forces.excess[j] = excess;
    const double w = weights_[j];
    ev.value += w * excess * excess;
    if (!with_gradient) continue;
    const Vec3 u = ft_vec / ft;  // ft > 0 since excess > 0
    const double mu = pressing ? friction_ : 0.0;
    // T = f_t − μ max(−f·n, 0): ∂f_t/∂f = u, ∂f_t/∂n = −(f·n) u.
    ev.a.segment<3>(3 * j) = 2.0 * w * excess * (u + mu * normal);
    ev.gn.row(j) = (2.0 * w * excess * (-fr * u + mu * f)).transpose();
  }
  return ev;
}

double SlidingObjective::value(const DesignState& state) const {
  const GarmentEnergies energies = energies_at(state.rest);
  double total = 0.0;
  for (int i = 0; i < static_cast<int>(poses_.size()); ++i)
    total += evaluate(state, energies, i, false).value;
  return total;
}

void SlidingObjective::add_gradient(const DesignState& state, VecX& /*d_x*/, VecX& d_rest) const {
  const GarmentEnergies energies = energies_at(state.rest);
  std::vector<Triplet> mixed;
  for (int i = 0; i < static_cast<int>(poses_.size()); ++i) {
    const PoseEvaluation ev = evaluate(state, energies, i, true);
    if (ev.value == 0.0) continue;
    mixed.clear();
    for (const RestDependentEnergy* e : energies.all()) e->add_mixed_rest(ev.posed.x, mixed);
    // f = −∂U/∂x, so ∂T/∂Xbar = −(∂²U/∂x∂Xbar)ᵀ a.
    for (const Triplet& t : mixed) d_rest[t.col()] -= t.value() * ev.a[t.row()];
  }
}

void SlidingObjective::add_embedding_gradient(const DesignState& state, VecX& d_s,
                                              VecX& d_y) const {
  const GarmentEnergies energies = energies_at(state.rest);
  std::vector<Triplet> hessian;
  for (int i = 0; i < static_cast<int>(poses_.size()); ++i) {
    const PoseEvaluation ev = evaluate(state, energies, i, true);
    if (ev.value == 0.0) continue;
    hessian.clear();
    const PosedGarment& pg = ev.posed;
    for (const RestDependentEnergy* e : energies.all()) e->add_hessian(pg.x, hessian, false);
    VecX gx = VecX::Zero(pg.x.size());  // ∂T/∂x_i = −H a
    for (const Triplet& t : hessian) gx[t.row()] -= t.value() * ev.a[t.col()];
    const std::vector<PointMotion>& motion = poses_[static_cast<std::size_t>(i)].motions;
    add_posed_position_gradient(pg, motion, gx, d_s, d_y);
    // Through the normals: n = c/|c|, c = x_u × x_v.
    for (int j = 0; j < num_garment_; ++j) {
      const Vec3 gn = ev.gn.row(j);
      if (gn.squaredNorm() == 0.0) continue;
      const Vec3 xu = pg.xu.row(j), xv = pg.xv.row(j);
      const Vec3 xuu = pg.xuu.row(j), xuv = pg.xuv.row(j), xvv = pg.xvv.row(j);
      const Vec3 c = xu.cross(xv);
      const double len = c.norm();
      const Vec3 normal = c / len;
      const Vec3 w = (gn - normal * normal.dot(gn)) / len;  // ∂T/∂c
      d_s[2 * j] += w.dot(xuu.cross(xv) + xu.cross(xuv));
      d_s[2 * j + 1] += w.dot(xuv.cross(xv) + xu.cross(xvv));
      const Vec3 t_u = xv.cross(w), t_v = w.cross(xu);  // ∂T/∂x_u, ∂T/∂x_v
      const LimitWeights& st = pg.stencils[static_cast<std::size_t>(j)];
      for (int k = 0; k < st.size(); ++k) {
        const int b = st.index[k];
        d_y.segment<3>(3 * b) += motion[b].linear.transpose() * (st.du[k] * t_u + st.dv[k] * t_v);
      }
    }
  }
}

SlidingObjective::PoseView SlidingObjective::pose_view(const DesignState& state, int pose) const {
  PoseEvaluation ev = evaluate(state, energies_at(state.rest), pose, false);
  return {std::move(ev.forces), std::move(ev.posed)};
}

VecX sliding_vertex_weights(const Garment& garment, const ResolutionReference& reference) {
  const VecX areas = garment_vertex_areas(garment);
  const double reference_area = resolution_or_own(reference, garment).vertex_area;
  VecX w(areas.size());
  for (Eigen::Index j = 0; j < areas.size(); ++j)
    w[j] = areas[j] > 0.0 ? reference_area / areas[j] : 0.0;
  return w;
}

}  // namespace tightfit
