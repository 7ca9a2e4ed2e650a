#include "tightfit/design/snap_detector.hpp"

namespace tightfit {

void SnapDetector::add_rising_trial(double alpha, double step, double rise,
                                    const DesignEvaluation& trial) {
  Trial t;
  t.alpha = alpha;
  t.fields.trials = 1;
  t.fields.rise = rise;
  t.fields.step = step;
  t.fields.move = trial.equilibrium_move;
  t.fields.vertex = trial.moved_vertex;
  t.fields.position = trial.moved_vertex_position;
  t.fields.label = trial.moved_vertex_label;
  for (Trial& earlier : trials_)
    if (alpha <= kStepRatio * earlier.alpha && rise >= kRiseRatio * earlier.fields.rise) {
      earlier.snapped = true;
      t.snapped = true;
    }
  trials_.push_back(std::move(t));
}

std::optional<SnapRecord> SnapDetector::record() const {
  std::optional<SnapRecord> out;
  int count = 0;
  double shortest = 0.0;
  for (const Trial& t : trials_) {
    if (!t.snapped) continue;
    ++count;
    if (!out || t.alpha < shortest) {
      out = t.fields;
      shortest = t.alpha;
    }
  }
  if (out) out->trials = count;
  return out;
}

std::optional<double> SnapDetector::shortest_snapped_alpha() const {
  std::optional<double> out;
  for (const Trial& t : trials_)
    if (t.snapped && (!out || t.alpha < *out)) out = t.alpha;
  return out;
}

}  // namespace tightfit
