#include "tightfit/objectives/all_poses_term.hpp"

#include <stdexcept>

#include "tightfit/common/error.hpp"

namespace tightfit {

AllPosesTerm::AllPosesTerm(std::shared_ptr<const DesignTerm> inner, const LimitSurface& surface,
                           std::vector<PoseMotions> poses)
    : inner_(std::move(inner)), surface_(surface), poses_(std::move(poses)) {
  if (!inner_) throw std::invalid_argument("AllPosesTerm: null term");
  if (poses_.empty())
    throw InputError("poses", inner_->name() + " in every pose: the scene has no poses");
  if (inner_->depends_on_embedding())
    throw InputError("poses", inner_->name() + " cannot be evaluated in every pose");
}

PosedGarment AllPosesTerm::posed(const DesignState& state, int pose) const {
  if (state.embedding == nullptr)
    throw std::logic_error("AllPosesTerm: the design state carries no embedding");
  return pose_garment(surface_, *state.embedding, poses_[static_cast<std::size_t>(pose)].motions);
}

double AllPosesTerm::pose_value(const DesignState& state, int pose) const {
  const PosedGarment p = posed(state, pose);
  return inner_->value(DesignState{p.x, state.rest, state.embedding});
}

double AllPosesTerm::value(const DesignState& state) const {
  double total = inner_->value(state);
  for (int i = 0; i < static_cast<int>(poses_.size()); ++i) total += pose_value(state, i);
  return total;
}

void AllPosesTerm::add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const {
  inner_->add_gradient(state, d_x, d_rest);
  VecX ignored(d_x.size());
  for (int i = 0; i < static_cast<int>(poses_.size()); ++i) {
    const PosedGarment p = posed(state, i);
    ignored.setZero();  // ∂T/∂x_i: add_embedding_gradient's part
    inner_->add_gradient(DesignState{p.x, state.rest, state.embedding}, ignored, d_rest);
  }
}

void AllPosesTerm::add_embedding_gradient(const DesignState& state, VecX& d_s, VecX& d_y) const {
  VecX d_x(state.x.size()), ignored(2 * state.rest.rows());
  for (int i = 0; i < static_cast<int>(poses_.size()); ++i) {
    const PosedGarment p = posed(state, i);
    d_x.setZero();
    ignored.setZero();
    inner_->add_gradient(DesignState{p.x, state.rest, state.embedding}, d_x, ignored);
    add_posed_position_gradient(p, poses_[static_cast<std::size_t>(i)].motions, d_x, d_s, d_y);
  }
}

}  // namespace tightfit
