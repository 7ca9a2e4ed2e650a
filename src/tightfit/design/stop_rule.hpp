#pragma once
/// Why a pattern optimization run ended (PatternOptimizer::run): one rule per way a run
/// can end, with a short name for result.json and a sentence for people.
#include <string>

namespace tightfit {

enum class StopRule {
  kGradient,          ///< converged: ‖∇T‖ fell below its tolerance
  kTargetValue,       ///< converged: T reached optimize/lbfgs/value_tolerance
  kStationary,        ///< converged: no progress, and the gradient agrees with finite differences
  kNoProgress,        ///< no progress, but the gradient disagrees with finite differences
  kSnapThrough,       ///< snap-throughs kept stopping the line search (jumps exhausted)
  kLineSearchFailed,  ///< no step along the gradient decreased T
  kIterationLimit,    ///< max_iterations reached
  kTimeLimit,         ///< the wall-clock budget ran out
  kInterrupted,       ///< stop_requested said so (Ctrl-C, SIGTERM)
};

/// "gradient", "target_value", "stationary", "no_progress", "snap_through",
/// "line_search_failed", "iteration_limit", "time_limit", "interrupted".
const char* stop_rule_name(StopRule rule);

/// One sentence: "converged: the gradient norm fell below its tolerance", ...
std::string stop_rule_words(StopRule rule);

/// True for the rules that mean a stationary point was reached (kGradient, kTargetValue,
/// kStationary).
bool stop_rule_converged(StopRule rule);

}  // namespace tightfit
