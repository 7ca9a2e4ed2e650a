#include "tightfit/design/line_search.hpp"

#include <algorithm>
#include <cmath>

#include "tightfit/common/stopwatch.hpp"
#include "tightfit/design/lbfgs.hpp"
#include "tightfit/design/snap_detector.hpp"

namespace tightfit {
namespace {

/// A descent direction at `current` and its slope ∇T·d: L-BFGS, or steepest descent
/// (clearing the memory) when the memory's direction does not descend.
VecX descent_direction(const DesignEvaluation& current, LbfgsMemory& memory, double& slope) {
  VecX d = lbfgs_direction(memory, current.gradient);
  slope = current.gradient.dot(d);
  if (!(slope < 0.0)) {
    memory = {};
    d = -current.gradient;
    slope = -current.gradient.squaredNorm();
  }
  return d;
}

/// The first trial's α: 1 for an L-BFGS step inside the bounds, else the largest α
/// within the trust radius, the growth cap and the compression bound.
double first_alpha(const DesignProblem& problem, const VecX& p, const VecX& d, bool scaled,
                   const LineSearchSettings& s) {
  const double move = max_point_move(d);
  double alpha = !scaled || move > s.trust_radius ? s.trust_radius / move : 1.0;
  if (s.growth_cap > 0.0 && alpha * move > s.growth_cap) alpha = s.growth_cap / move;
  if (s.max_compression > 0.0)
    alpha = std::min(alpha, problem.max_step_keeping_areas(p, d, s.max_compression));
  return alpha;
}

/// Minimizer of the quadratic through T(0), T'(0) and T(α), kept in [0.1, 0.5]·α.
double backtrack(double alpha, double rise_over_slope_line, double slope) {
  const double curvature = 2.0 * rise_over_slope_line;
  const double next = curvature > 0.0 ? -slope * alpha * alpha / curvature : 0.5 * alpha;
  return std::clamp(next, 0.1 * alpha, 0.5 * alpha);
}

}  // namespace

void add_trial_counters(OptimizationIteration& record, const DesignEvaluation& trial,
                        double seconds) {
  ++record.line_search_trials;
  record.seconds_forward += seconds - trial.seconds_objective;
  record.seconds_objective += trial.seconds_objective;
  record.newton_iterations += trial.newton_iterations;
  record.chord_steps += trial.chord_steps;
  record.force_accepted_steps += trial.force_accepted_steps;
  record.factorizations += trial.factorizations;
  record.seconds_assembly += trial.seconds_assembly;
  record.seconds_factorization += trial.seconds_factorization;
}

LineSearchResult line_search(DesignProblem& problem, const VecX& p, const DesignEvaluation& current,
                             LbfgsMemory& memory, const LineSearchSettings& settings,
                             OptimizationIteration& record,
                             const std::function<bool()>& should_stop) {
  LineSearchResult out;
  SnapDetector snaps;
  for (int attempt = 0; attempt < 2 && !out.accepted && !out.stopped; ++attempt) {
    snaps.reset();
    if (attempt == 1) {
      if (memory.s.empty()) break;  // steepest descent already failed
      memory = {};
    }
    double slope = 0.0;
    const VecX d = descent_direction(current, memory, slope);
    if (!(max_point_move(d) > 0.0)) break;
    double alpha = first_alpha(problem, p, d, !memory.s.empty(), settings);
    for (int t = 0; t < settings.max_trials; ++t) {
      // A stop request ends the iteration between two trials: a hard line search can
      // take minutes, and the last accepted iteration is what a stop keeps anyway.
      if (t > 0 && should_stop && should_stop()) {
        out.stopped = true;
        break;
      }
      const auto t_trial = SteadyClock::now();
      out.trial = problem.evaluate(p + alpha * d, false);
      add_trial_counters(record, out.trial, seconds_since(t_trial));
      if (!out.trial.ok) {
        ++record.failed_solves;
        alpha *= 0.5;
        continue;
      }
      const VecX step = alpha * d;
      record.max_solved_move = std::max(record.max_solved_move, max_point_move(step));
      const double line = out.trial.value - current.value - alpha * slope;
      if (out.trial.value <= current.value + settings.armijo * alpha * slope) {
        const auto t_gradient = SteadyClock::now();
        const bool gradient_ok = problem.add_gradient(out.trial);
        record.seconds_adjoint += seconds_since(t_gradient);
        record.factorizations += out.trial.adjoint_factorizations;
        if (gradient_ok) {
          out.accepted = true;
          out.alpha = alpha;
          out.step = step;
          break;
        }
        ++record.failed_solves;
        alpha *= 0.5;
        continue;
      }
      if (const double rise = out.trial.value - current.value; rise > 0.0)
        snaps.add_rising_trial(alpha, max_point_move(step), rise, out.trial);
      alpha = backtrack(alpha, line, slope);
    }
    out.snap = snaps.record();
    const auto jump = snaps.shortest_snapped_alpha();
    out.jump_step = jump ? VecX(*jump * d) : VecX();
  }
  return out;
}

}  // namespace tightfit
