#pragma once
/// The progress an optimize run prints to stdout: a header naming the columns once,
/// then one row per L-BFGS iteration ("12/150", objective, gradient norm, step, its
/// cost, elapsed time and the time left at most), in the full mode followed by the
/// weighted value of every objective term, and a line per remeshing.
#include <string>
#include <vector>

#include "tightfit/design/optimization_state.hpp"

namespace tightfit::app {

/// "42 s", "1m40s", "2h05m".
std::string duration_text(double seconds);

class OptimizeProgress {
 public:
  /// `term_names`: the objective's terms in order; `max_iterations`: the run's limit;
  /// `terse`: rows only (no per-term line).
  OptimizeProgress(std::vector<std::string> term_names, int max_iterations, bool terse);

  /// The column header: what the columns mean (three lines), then their names.
  std::string header() const;
  /// The row of iteration `it`, then (full mode) its terms line and (when `it` remeshed)
  /// the remeshing line; each line ends with '\n'.
  std::string lines(const OptimizationIteration& it) const;

  /// Prints header() once, before the first iteration's lines, then lines(it); flushes.
  void print(const OptimizationIteration& it);

 private:
  std::string row(const OptimizationIteration& it) const;
  std::string terms(const OptimizationIteration& it) const;

  std::vector<std::string> names_;
  int max_iterations_ = 0;
  bool terse_ = false;
  bool header_printed_ = false;
  int iteration_width_ = 6;
};

}  // namespace tightfit::app
