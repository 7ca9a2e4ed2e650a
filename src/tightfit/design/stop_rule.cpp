#include "tightfit/design/stop_rule.hpp"

namespace tightfit {

const char* stop_rule_name(StopRule rule) {
  switch (rule) {
    case StopRule::kGradient:
      return "gradient";
    case StopRule::kTargetValue:
      return "target_value";
    case StopRule::kStationary:
      return "stationary";
    case StopRule::kNoProgress:
      return "no_progress";
    case StopRule::kSnapThrough:
      return "snap_through";
    case StopRule::kLineSearchFailed:
      return "line_search_failed";
    case StopRule::kIterationLimit:
      return "iteration_limit";
    case StopRule::kTimeLimit:
      return "time_limit";
    case StopRule::kInterrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string stop_rule_words(StopRule rule) {
  switch (rule) {
    case StopRule::kGradient:
      return "converged: the gradient norm fell below its tolerance";
    case StopRule::kTargetValue:
      return "converged: the objective reached its target value";
    case StopRule::kStationary:
      return "converged: no progress over the last iterations, and the gradient there agrees "
             "with finite differences (a stationary point)";
    case StopRule::kNoProgress:
      return "not converged: no progress over the last iterations, but the gradient there "
             "disagrees with finite differences (a kink or an inexact gradient)";
    case StopRule::kSnapThrough:
      return "not converged: the fit kept snapping to another equilibrium with a higher "
             "objective";
    case StopRule::kLineSearchFailed:
      return "not converged: no step along the search direction decreased the objective";
    case StopRule::kIterationLimit:
      return "not converged: the iteration limit was reached";
    case StopRule::kTimeLimit:
      return "not converged: the time limit was reached";
    case StopRule::kInterrupted:
      return "not converged: interrupted";
  }
  return "unknown";
}

bool stop_rule_converged(StopRule rule) {
  return rule == StopRule::kGradient || rule == StopRule::kTargetValue ||
         rule == StopRule::kStationary;
}

}  // namespace tightfit
