/// `tightfit check-gradient SCENE`: the adjoint design gradient of the scene's
/// "optimize" objective against fourth-order central finite differences of the whole
/// simulate-then-evaluate pipeline, along random directions in the design space; for
/// the weighted total and for every term alone. Exits 0 after printing; with
/// `--max-error E` it exits 4 when some relative error exceeds E. With `--at DIR` the
/// check is made at the pattern and equilibrium of DIR/checkpoint.json (an optimize run
/// of the same scene, remeshed or not), e.g. where a run stalled.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <filesystem>

#include "cli_checks.hpp"
#include "command_registry.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/design/adjoint_check.hpp"
#include "tightfit/design/pattern_optimizer.hpp"
#include "tightfit/scene/checkpoint_inputs.hpp"
#include "tightfit/scene/loader.hpp"
#include "tightfit/scene/optimization_checkpoint.hpp"
#include "tightfit/scene/optimization_setup.hpp"

namespace tightfit::app {
namespace {

struct CheckArgs {
  std::string scene;
  int directions = 3;
  double step = 0.0;
  unsigned seed = 1;
  double perturb = 0.0;
  double max_error = 0.0;
  std::string at;  // optimize run folder whose checkpoint.json gives the pattern
};

/// Prints the checks of one row label and returns the largest error. A term's error is
/// relative to the larger of its own finite difference and the total's along the same
/// direction (`total`; empty for the total itself): a term whose derivative is 1e-18
/// where the total's is 1e-3 matters to nobody, and its round-off must not read as a
/// 100 % error.
double report(const std::string& label, const std::vector<DirectionalCheck>& checks,
              const std::vector<DirectionalCheck>& total = {}) {
  double worst = 0.0;
  for (size_t k = 0; k < checks.size(); ++k) {
    const DirectionalCheck& c = checks[k];
    double error = c.relative_error;
    if (k < total.size()) {
      const double scale =
          std::max(std::abs(c.finite_difference), std::abs(total[k].finite_difference));
      if (scale > 0.0) error = std::abs(c.adjoint - c.finite_difference) / scale;
    }
    std::printf("  %-22s %3zu  %+.12e  %+.12e  %.2e%s\n", label.c_str(), k, c.adjoint,
                c.finite_difference, error,
                c.hessian_shift > 0.0 ? "  (adjoint Hessian shifted: inexact)" : "");
    worst = std::max(worst, error);
  }
  return worst;
}

void run_check_gradient(const CheckArgs& args) {
  OptimizationScene input = read_optimization_scene(args.scene);
  auto scene = load_scene(input.scene);
  auto sim = make_simulation(*scene);
  // The terms' weights refer to the scene's initial mesh, as in `tightfit optimize`.
  input.optimization.resolution = resolution_of(sim->garment());
  const auto objective = build_objective(input.optimization, *sim);
  const std::vector<std::string> names = term_names(*objective);
  // Read before the initial solve, so that a bad file fails at once.
  std::optional<OptimizationCheckpoint> at;
  const std::filesystem::path at_file = std::filesystem::path(args.at) / "checkpoint.json";
  if (!args.at.empty()) at = read_checkpoint_for(at_file, names, nullptr);
  const NewtonReport initial = sim->solve();
  std::printf(
      "tightfit check-gradient: %d garment vertices, initial equilibrium in %d Newton "
      "iterations (residual %.2e N)\n",
      sim->garment().num_garment_vertices(), initial.iterations, initial.final_force_norm);
  const EmbeddedState equilibrium = sim->problem().state();
  const Points2 initial_rest = sim->garment().rest_positions();
  if (at) std::printf("  at %s, iteration %d\n", at_file.c_str(), at->iteration);

  GradientCheckOptions options;
  options.directions = args.directions;
  options.step = args.step;
  options.seed = args.seed;
  std::printf("  %-22s %3s  %-19s  %-19s  %s\n", "term", "dir", "adjoint dT/dp.d",
              "finite difference", "rel. error");
  double worst = 0.0;
  const OptimizationSpec& spec = input.optimization;
  // The objective of the check: the whole objective (term < 0) or its entry `term`, built
  // for the given simulation (also after a remeshing, which rebuilds it).
  auto objective_of = [&spec](int term) {
    return [&spec, term](const GarmentSimulation& g) -> std::shared_ptr<DesignTermSum> {
      auto whole = build_objective(spec, g);
      if (term < 0) return whole;
      auto single = std::make_shared<DesignTermSum>();
      single->add(whole->entries()[static_cast<size_t>(term)].term,
                  whole->entries()[static_cast<size_t>(term)].weight);
      return single;
    };
  };
  auto check = [&](int term) {
    // Every check starts from the scene's pattern, or from the checkpoint's (a remeshed
    // checkpoint changes the garment, so each check then gets a simulation of its own).
    std::unique_ptr<GarmentSimulation> own;
    GarmentSimulation* s = sim.get();
    if (at) {
      own = make_simulation(*scene);
      s = own.get();
    }
    s->set_rest_positions(initial_rest);
    s->set_state(equilibrium);
    const auto factory = objective_of(term);
    DesignProblem problem(*s, factory(*s), spec.problem, factory);
    VecX p = problem.initial_parameters();
    if (at) {
      PatternOptimizer optimizer(problem, spec.optimizer);
      try {
        optimizer.resume(*at);
      } catch (const InputError& e) {
        if (e.source() == at_file.string()) throw;
        throw InputError(at_file.string(), e.what());
      }
      p = problem.accepted_parameters();
    }
    if (args.perturb > 0.0)
      p += args.perturb * problem.mean_boundary_edge() *
           random_design_direction(p.size(), args.seed + 1000);
    return check_design_gradient(problem, p, options);
  };
  const std::vector<DirectionalCheck> total = check(-1);
  worst = std::max(worst, report("total", total));
  if (names.size() > 1)
    for (size_t k = 0; k < names.size(); ++k)
      worst = std::max(worst, report(names[k], check(static_cast<int>(k)), total));
  std::printf("  largest relative error: %.3e\n", worst);
  if (args.max_error > 0.0 && worst > args.max_error) {
    std::fprintf(stderr, "error: relative error %.3e exceeds --max-error %.3e\n", worst,
                 args.max_error);
    std::exit(4);
  }
}

const CommandRegistration kCheckGradient{
    "check-gradient", [](CLI::App& root) {
      auto* cmd = root.add_subcommand(
          "check-gradient",
          "Compare the adjoint design gradient of the scene's \"optimize\" objective with finite "
          "differences of simulate-then-evaluate along random directions (total and per term).");
      cmd->footer(
          "Examples:\n  tightfit check-gradient examples/optimize_sleeve_stretch.json\n  tightfit "
          "check-gradient examples/optimize_pants_stretch.json --at out/pants");
      auto args = std::make_shared<CheckArgs>();
      cmd->add_option("scene", args->scene, "Scene file with an \"optimize\" section")->required();
      cmd->add_option("--directions", args->directions, "Random directions per term (default 3)")
          ->check(positive_number());
      cmd->add_option("--step", args->step,
                      "Finite-difference step h in m (default 1e-5 x mean boundary edge)")
          ->check(non_negative_number());
      cmd->add_option("--seed", args->seed, "Seed of the random directions (default 1)");
      cmd->add_option("--perturb", args->perturb,
                      "Check at the pattern moved randomly by this fraction of the mean boundary "
                      "edge (regularizers vanish on the initial pattern; default 0)")
          ->check(non_negative_number());
      cmd->add_option("--at", args->at,
                      "Check at the pattern of DIR/checkpoint.json (an optimize run of this "
                      "scene) instead of the scene's initial pattern");
      cmd->add_option("--max-error", args->max_error,
                      "Exit with status 4 when a relative error exceeds this")
          ->check(non_negative_number());
      cmd->callback([args] { run_check_gradient(*args); });
    }};

}  // namespace
}  // namespace tightfit::app
