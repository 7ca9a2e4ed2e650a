/// `tightfit check-gradient SCENE`: the adjoint design gradient of the scene's
/// "optimize" objective against fourth-order central finite differences of the whole
/// simulate-then-evaluate pipeline, along random directions in the design space; for
/// the weighted total and for every term alone. Exits 0 after printing; with
/// `--max-error E` it exits 4 when some relative error exceeds E.
#include <cstdio>
#include <cstdlib>

#include "cli_checks.hpp"
#include "command_registry.hpp"
#include "tightfit/io/optimization_setup.hpp"
#include "tightfit/design/adjoint_check.hpp"
#include "tightfit/design/optimization_checkpoint.hpp"
#include "tightfit/io/scene_loader.hpp"

namespace tightfit::app {
namespace {

struct CheckArgs {
  std::string scene;
  int directions = 3;
  double step = 0.0;
  unsigned seed = 1;
  double perturb = 0.0;
  double max_error = 0.0;
};

double report(const std::string& label, const std::vector<DirectionalCheck>& checks) {
  double worst = 0.0;
  for (size_t k = 0; k < checks.size(); ++k) {
    const DirectionalCheck& c = checks[k];
    std::printf("  %-22s %3zu  %+.12e  %+.12e  %.2e%s\n", label.c_str(), k, c.adjoint,
                c.finite_difference, c.relative_error,
                c.hessian_shift > 0.0 ? "  (adjoint Hessian shifted: inexact)" : "");
    worst = std::max(worst, c.relative_error);
  }
  return worst;
}

void run_check_gradient(const CheckArgs& args) {
  OptimizationScene input = read_optimization_scene(args.scene);
  auto scene = load_scene(input.scene);
  auto sim = make_simulation(*scene);
  const auto objective = build_objective(input.optimization, *sim);
  const std::vector<std::string> names = term_names(*objective);
  const NewtonReport initial = sim->solve();
  std::printf(
      "tightfit check-gradient: %d garment vertices, initial equilibrium in %d Newton "
      "iterations (residual %.2e N)\n",
      sim->garment().num_garment_vertices, initial.iterations, initial.final_force_norm);
  const EmbeddedState equilibrium = sim->problem().state();
  const Points2 initial_rest = sim->garment().rest_positions();

  GradientCheckOptions options;
  options.directions = args.directions;
  options.step = args.step;
  options.seed = args.seed;
  std::printf("  %-22s %3s  %-19s  %-19s  %s\n", "term", "dir", "adjoint dT/dp.d",
              "finite difference", "rel. error");
  double worst = 0.0;
  auto check = [&](const std::string& label, std::shared_ptr<const DesignTermSum> terms) {
    sim->set_rest_positions(initial_rest);  // every check starts from the scene's pattern
    sim->set_state(equilibrium);
    DesignProblem problem(*sim, std::move(terms), input.optimization.problem);
    VecX p = problem.initial_parameters();
    if (args.perturb > 0.0)
      p += args.perturb * problem.mean_boundary_edge() *
           random_design_direction(p.size(), args.seed + 1000);
    worst = std::max(worst, report(label, check_design_gradient(problem, p, options)));
  };
  check("total", objective);
  if (names.size() > 1)
    for (size_t k = 0; k < names.size(); ++k) {
      auto single = std::make_shared<DesignTermSum>();
      single->add(objective->entries()[k].term, objective->entries()[k].weight);
      check(names[k], single);
    }
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
      cmd->add_option("--max-error", args->max_error,
                      "Exit with status 4 when a relative error exceeds this")
          ->check(non_negative_number());
      cmd->callback([args] { run_check_gradient(*args); });
    }};

}  // namespace
}  // namespace tightfit::app
