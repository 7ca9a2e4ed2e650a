#include "optimize_progress.hpp"

#include <algorithm>
#include <cstdio>

namespace tightfit::app {
namespace {

/// printf into a std::string.
template <typename... Args>
std::string format(const char* pattern, Args... args) {
  const int n = std::snprintf(nullptr, 0, pattern, args...);
  std::string text(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
  std::snprintf(text.data(), text.size(), pattern, args...);
  text.resize(static_cast<std::size_t>(std::max(n, 0)));
  return text;
}

/// Width of the terms line before it wraps.
constexpr std::size_t kTermsWidth = 96;

}  // namespace

std::string duration_text(double seconds) {
  if (seconds < 60.0) return format("%.0f s", seconds);
  if (seconds < 3600.0)
    return format("%dm%02ds", static_cast<int>(seconds / 60.0), static_cast<int>(seconds) % 60);
  return format("%dh%02dm", static_cast<int>(seconds / 3600.0),
                static_cast<int>(seconds / 60.0) % 60);
}

OptimizeProgress::OptimizeProgress(std::vector<std::string> term_names, int max_iterations,
                                   bool terse)
    : names_(std::move(term_names)), max_iterations_(max_iterations), terse_(terse) {
  const int digits = static_cast<int>(std::to_string(std::max(max_iterations, 0)).size());
  iteration_width_ = std::max(6, 2 * digits + 1);
}

std::string OptimizeProgress::header() const {
  std::string text =
      "  T: objective; |g|: norm of dT/dp; step: largest move of a boundary point (m); trials:\n"
      "  line-search trials; newton: Newton steps of the forward solves, chord: of them reusing\n"
      "  a factorization; chol: Cholesky factorizations; left: at most, at the mean pace so far\n";
  text += format("  %*s  %11s  %9s  %8s  %6s  %6s  %5s  %4s  %8s  %s\n", iteration_width_, "it",
                 "T", "|g|", "step", "trials", "newton", "chord", "chol", "elapsed", "left");
  return text;
}

std::string OptimizeProgress::row(const OptimizationIteration& it) const {
  const std::string iteration = format("%d/%d", it.iteration, max_iterations_);
  std::string text = format(
      "  %*s  %11.4e  %9.3e  %8.2e  %6d  %6d  %5d  %4d  %8s", iteration_width_, iteration.c_str(),
      it.value, it.gradient_norm, it.max_point_move, it.line_search_trials, it.newton_iterations,
      it.chord_steps, it.factorizations, format("%.1f s", it.seconds).c_str());
  if (it.iteration > 0 && it.iteration < max_iterations_)
    text += "  " + duration_text(it.seconds / it.iteration * (max_iterations_ - it.iteration));
  if (it.failed_solves > 0) text += format("  (failed trials %d)", it.failed_solves);
  if (it.snap)
    text += format("  (snapped trials %d: T +%.2e, garment vertex %d moved %.1f mm)",
                   it.snap->trials, it.snap->rise, it.snap->vertex, 1e3 * it.snap->move);
  if (it.jump) text += "  (jumped through the snap-through: continuing from that equilibrium)";
  if (it.hessian_shift > 0.0)
    text += format("  [adjoint H shifted by %.1e: inexact]", it.hessian_shift);
  return text + "\n";
}

std::string OptimizeProgress::terms(const OptimizationIteration& it) const {
  const std::string indent(static_cast<std::size_t>(iteration_width_) + 4, ' ');
  std::string text, line = indent;
  for (std::size_t k = 0; k < names_.size() && k < it.term_values.size(); ++k) {
    const std::string item = format("%s %.4e", names_[k].c_str(), it.term_values[k]);
    if (line.size() > indent.size() && line.size() + 2 + item.size() > kTermsWidth) {
      text += line + "\n";
      line = indent;
    }
    line += (line.size() > indent.size() ? "  " : "") + item;
  }
  if (line.size() > indent.size()) text += line + "\n";
  return text;
}

std::string OptimizeProgress::lines(const OptimizationIteration& it) const {
  std::string text = row(it);
  if (!terse_) text += terms(it);
  if (const auto& r = it.remesh) {
    std::string pieces;
    for (const std::string& p : r->pieces) pieces += (pieces.empty() ? "" : ", ") + p;
    if (r->failure.empty())
      text += format(
          "    remeshed %s (min angle %.1f -> %.1f deg): T %.6e, %d design parameters, "
          "%d garment vertices, newton %d, %.1f s\n",
          pieces.c_str(), r->min_angle_before, r->min_angle_after, r->value, r->parameters,
          r->garment_vertices, r->newton_iterations, r->seconds);
    else
      text += "    remeshing " + pieces + " failed and was undone: " + r->failure + "\n";
  }
  return text;
}

void OptimizeProgress::print(const OptimizationIteration& it) {
  if (!header_printed_) {
    std::fputs(header().c_str(), stdout);
    header_printed_ = true;
  }
  std::fputs(lines(it).c_str(), stdout);
  std::fflush(stdout);
}

}  // namespace tightfit::app
