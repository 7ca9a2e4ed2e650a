#include "tightfit/objectives/pinned_traction_regularizer.hpp"

#include <stdexcept>

#include "tightfit/common/error.hpp"

namespace tightfit {

/// At one state: per pinned vertex its normal frame, a = ∂T/∂g and ∂T/∂n.
struct PinnedTractionRegularizer::Evaluation {
  double value = 0.0;
  VecX a;                              // 3·n_g, nonzero at pinned vertices
  std::vector<LimitWeights> stencils;  // per pinned vertex
  std::vector<Vec3> xu, xv, gn;        // per pinned vertex
};

PinnedTractionRegularizer::PinnedTractionRegularizer(const Garment& garment,
                                                     const SimulationMaterials& materials,
                                                     const LimitSurface& surface,
                                                     const ResolutionReference& reference)
    : surface_(surface),
      pinned_(garment.topology->pinned),
      topology_(garment.topology),
      fabric_(materials.fabric),
      seam_(materials.seam) {
  if (pinned_.empty()) throw InputError("pinned traction", "the garment has no pinned vertices");
  // A pin holds the traction along its share of the pinned rim: w = reference edge / share.
  const VecX lengths = pinned_vertex_lengths(garment);
  const double edge = resolution_or_own(reference, garment).boundary_edge;
  weights_.resize(pinned_.size());
  for (std::size_t k = 0; k < pinned_.size(); ++k) {
    const double share = lengths[pinned_[k]];
    weights_[k] = share > 0.0 ? edge / share : 1.0;
  }
}

PinnedTractionRegularizer::~PinnedTractionRegularizer() = default;

GarmentEnergies PinnedTractionRegularizer::energies_at(const Points2& rest) const {
  return GarmentEnergies(topology_, rest, fabric_, seam_);
}

PinnedTractionRegularizer::Evaluation PinnedTractionRegularizer::evaluate(
    const DesignState& state) const {
  if (state.embedding == nullptr)
    throw std::logic_error("PinnedTractionRegularizer: the design state carries no embedding");
  VecX g = VecX::Zero(state.x.size());
  for (const RestDependentEnergy* e : energies_at(state.rest).all()) e->add_gradient(state.x, g);
  Evaluation ev;
  ev.a = VecX::Zero(state.x.size());
  const std::size_t n = pinned_.size();
  ev.stencils.resize(n);
  ev.xu.resize(n);
  ev.xv.resize(n);
  ev.gn.resize(n);
  const Points3& y = state.embedding->body;
  for (std::size_t k = 0; k < n; ++k) {
    const int i = pinned_[k];
    LimitWeights& w = ev.stencils[k];
    surface_.weights(state.embedding->garment[static_cast<std::size_t>(i)], w);
    Vec3 xu = Vec3::Zero(), xv = Vec3::Zero();
    for (int j = 0; j < w.size(); ++j) {
      xu += w.du[j] * y.row(w.index[j]).transpose();
      xv += w.dv[j] * y.row(w.index[j]).transpose();
    }
    const Vec3 normal = xu.cross(xv).normalized();
    const Vec3 gi = g.segment<3>(3 * i);
    const Vec3 tangential = gi - normal * normal.dot(gi);
    const double wk = weights_[k];
    ev.value += wk * tangential.squaredNorm();
    ev.a.segment<3>(3 * i) = 2.0 * wk * tangential;
    ev.xu[k] = xu;
    ev.xv[k] = xv;
    ev.gn[k] = -2.0 * wk * normal.dot(gi) * gi;
  }
  return ev;
}

double PinnedTractionRegularizer::value(const DesignState& state) const {
  return evaluate(state).value;
}

void PinnedTractionRegularizer::add_gradient(const DesignState& state, VecX& d_x,
                                             VecX& d_rest) const {
  const Evaluation ev = evaluate(state);
  const GarmentEnergies energies = energies_at(state.rest);
  std::vector<Triplet> t;
  for (const RestDependentEnergy* e : energies.all()) e->add_hessian(state.x, t, false);
  for (const Triplet& h : t) d_x[h.row()] += h.value() * ev.a[h.col()];
  t.clear();
  for (const RestDependentEnergy* e : energies.all()) e->add_mixed_rest(state.x, t);
  for (const Triplet& m : t) d_rest[m.col()] += m.value() * ev.a[m.row()];
}

// Pinned vertices do not move on the surface (no DOF), so only the body's part is given.
void PinnedTractionRegularizer::add_embedding_gradient(const DesignState& state, VecX& /*d_s*/,
                                                       VecX& d_y) const {
  const Evaluation ev = evaluate(state);
  for (std::size_t k = 0; k < pinned_.size(); ++k) {
    const Vec3 c = ev.xu[k].cross(ev.xv[k]);
    const double len = c.norm();
    const Vec3 normal = c / len;
    const Vec3 w = (ev.gn[k] - normal * normal.dot(ev.gn[k])) / len;  // ∂T/∂c
    const Vec3 t_u = ev.xv[k].cross(w), t_v = w.cross(ev.xu[k]);      // ∂T/∂x_u, ∂T/∂x_v
    const LimitWeights& st = ev.stencils[k];
    for (int j = 0; j < st.size(); ++j)
      d_y.segment<3>(3 * st.index[j]) += st.du[j] * t_u + st.dv[j] * t_v;
  }
}

}  // namespace tightfit
