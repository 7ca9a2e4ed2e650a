/// The line search's snap-through test (design/snap_detector.hpp): rises that do not
/// shrink with the step are a snap, rises that shrink like a smooth function's are not.
#include <gtest/gtest.h>

#include "tightfit/design/snap_detector.hpp"

namespace tightfit::snap_detector_test {

DesignEvaluation trial_moving(int vertex, double move) {
  DesignEvaluation e;
  e.ok = true;
  e.equilibrium_move = move;
  e.moved_vertex = vertex;
  e.moved_vertex_position = Vec3(0.01 * vertex, 0.8, 0.02);
  e.moved_vertex_label = "pieces 'left_front', 'right_front'";
  return e;
}

TEST(SnapDetector, RisesOfASmoothObjectiveAreNoSnap) {
  // T(α) = T0 − α + 50 α²: above T0 for α > 0.02, the rise shrinking quadratically.
  SnapDetector d;
  for (double alpha : {1.0, 0.5, 0.25, 0.1, 0.05}) {
    const double rise = -alpha + 50.0 * alpha * alpha;
    if (rise > 0.0) d.add_rising_trial(alpha, 1e-3 * alpha, rise, trial_moving(1, 1e-4 * alpha));
  }
  EXPECT_FALSE(d.record());
}

TEST(SnapDetector, ARiseThatStaysAsTheStepShrinksIsASnap) {
  SnapDetector d;
  d.add_rising_trial(1.0, 1e-3, 9.0e-5, trial_moving(8, 0.0110));
  EXPECT_FALSE(d.record()) << "one rising trial says nothing about continuity";
  d.add_rising_trial(0.5, 5e-4, 8.8e-5, trial_moving(8, 0.0108));
  EXPECT_FALSE(d.record()) << "a step halved is not yet short enough to tell";
  d.add_rising_trial(0.1, 1e-4, 8.6e-5, trial_moving(9, 0.0105));
  const auto snap = d.record();
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->trials, 3);            // 0.1 pairs with both earlier trials
  EXPECT_DOUBLE_EQ(snap->rise, 8.6e-5);  // the shortest snapped trial's
  EXPECT_DOUBLE_EQ(snap->step, 1e-4);
  EXPECT_DOUBLE_EQ(snap->move, 0.0105);
  EXPECT_EQ(snap->vertex, 9);
  EXPECT_EQ(snap->label, "pieces 'left_front', 'right_front'");
  d.reset();
  EXPECT_FALSE(d.record()) << "a new search direction starts afresh";
}

TEST(SnapDetector, ARiseThatShrinksLinearlyIsNoSnap) {
  // A kink (T rising like |α| past a crease of the objective) is continuous: a step
  // shortened 10-fold rises 10-fold less.
  SnapDetector d;
  d.add_rising_trial(1.0, 1e-3, 1e-4, trial_moving(2, 1e-3));
  d.add_rising_trial(0.1, 1e-4, 1e-5, trial_moving(2, 1e-4));
  EXPECT_FALSE(d.record());
}

}  // namespace tightfit::snap_detector_test
