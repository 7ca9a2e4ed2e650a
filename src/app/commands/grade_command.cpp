/// `tightfit grade DESIGN BODIES --out DIR [--jobs N | --body NAME | --gather]`: one
/// design optimized on every body of a population (grading), each body in its own
/// folder DIR/bodies/NAME (app/commands/grade_body.hpp: one idempotent, resumable
/// invocation per body), then gathered into DIR/grade.json (grade/summary.hpp),
/// DIR/grade.html (grade/report.hpp) and the nest of the graded pieces as
/// DIR/nest.svg, nest.pdf and nest.dxf (patterns/nest.hpp).
///
///  * no --body, no --gather: every body, --jobs N at a time as processes of this binary
///    (grade_jobs.hpp; logs in DIR/logs/NAME.log), then the gathering;
///  * --body NAME: that body only, in this process (what GNU parallel or a Slurm array
///    task runs);
///  * --gather: the gathering only.
/// Exit code: 0 when every body (or the --body) is graded; 2 for bad input (nothing is
/// run: an unreadable design or bodies file, two bodies of one name, an unknown
/// --body); otherwise 10 + the number of bodies not graded (failed, or not run yet when
/// gathering), at most 110.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "cli_checks.hpp"
#include "command_registry.hpp"
#include "grade_body.hpp"
#include "grade_jobs.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/nearest_word.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/common/staging_folder.hpp"
#include "tightfit/grade/report.hpp"
#include "tightfit/grade/summary.hpp"
#include "tightfit/patterns/nest.hpp"

namespace tightfit::app {
namespace {

namespace fs = std::filesystem;

/// Exit code of a grading with `failed` bodies not graded.
int grade_exit_code(int failed) { return failed == 0 ? 0 : 10 + std::min(failed, 100); }

struct GradeOptions {
  std::string design;
  std::string bodies;
  std::string out;
  std::string body;
  bool gather_only = false;
  int jobs = 1;
  int max_iterations = -1;
  std::string nest_seam;
  bool force = false;
};

/// Writes grade.json, grade.html and the nest files into DIR; returns the number of
/// bodies not graded.
int gather(const GradeOptions& o, const std::vector<GradeBody>& bodies) {
  const GradeSummary summary = gather_grade(bodies, o.out, o.design, o.bodies);
  std::vector<NestSize> sizes;
  for (const GradedBody& b : summary.bodies)
    if (b.pattern) sizes.push_back({b.name, &*b.pattern});
  std::optional<Nest> nest;
  if (!sizes.empty()) nest = make_nest(sizes, o.nest_seam);
  OutputDirectory out(o.out, o.force, "grade");
  out.commit_in_place();  // other invocations may be grading bodies in it right now
  write_json_atomically(out.file("grade.json"), summary.json, 2);
  write_grade_report(out.file("grade.html"), summary, nest ? &*nest : nullptr);
  std::vector<std::string> files = {"grade.json", "grade.html"};
  if (nest)
    for (const std::string& f : write_nest_files(out.staging(), *nest)) files.push_back(f);
  out.commit();
  std::printf("tightfit grade: %d of %zu bodies graded\n",
              static_cast<int>(summary.bodies.size()) - summary.not_done, summary.bodies.size());
  for (const GradedBody& b : summary.bodies) {
    std::printf("  %-16s %s", b.name.c_str(), b.status.c_str());
    if (b.status == "done")
      std::printf("  objective ratio %.4f, %s iterations",
                  b.entry["objective"]["ratio"].get<double>(),
                  b.entry["iterations"].dump().c_str());
    if (!b.error.empty()) std::printf(": %s", b.error.c_str());
    std::printf("\n");
  }
  for (const auto& f : files) std::printf("  %s\n", (fs::path(o.out) / f).c_str());
  std::fflush(stdout);
  return summary.not_done;
}

/// Prepares the grading folder (the output-folder rule) and marks it. Bodies graded at
/// once by separate invocations (GNU parallel, Slurm) may all find it missing: it is
/// made with its marker in a temporary folder beside it and renamed into place, so that
/// none of them ever sees it without the marker (and refuses it as a folder tightfit did
/// not write).
void prepare_grade_folder(const fs::path& dir, bool force) {
  std::error_code ec;
  if (!dir.empty() && !fs::exists(dir, ec)) {
    const fs::path real = fs::weakly_canonical(fs::absolute(dir), ec);
    fs::create_directories(real.parent_path(), ec);
    try {
      const StagingFolder staging = make_staging_folder(real, real.parent_path());
      const fs::path fresh = staging.path / "new";
      if (fs::create_directory(fresh, ec)) {
        mark_output_folder(fresh, "grade");
        fs::rename(fresh, real, ec);  // fails when another invocation was first: fine
      }
      ::close(staging.fd);
      fs::remove_all(staging.path, ec);
    } catch (const InputError&) {
      // no staging folder beside it: prepare_output_folder below says what is wrong
    }
  }
  prepare_output_folder(dir, force);
  mark_output_folder(dir, "grade");
}

void run_grade(const GradeOptions& o) {
  // Everything is read and checked before the output folder is touched.
  const GradeDesign design = read_grade_design(o.design);
  const std::vector<GradeBody> bodies = read_grade_bodies(o.bodies);
  std::vector<std::string> names;
  for (const GradeBody& b : bodies) names.push_back(b.name);
  const auto chosen = std::find(names.begin(), names.end(), o.body);
  if (!o.body.empty() && chosen == names.end()) {
    const std::string near = nearest_word(o.body, names);
    throw InputError("--body", "no body \"" + o.body + "\" in " + o.bodies +
                                   (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
  }
  prepare_grade_folder(o.out, o.force);

  if (!o.body.empty()) {
    const GradeBody& body = bodies[static_cast<size_t>(chosen - names.begin())];
    if (grade_body(design, body, o.out, o.max_iterations) == BodyOutcome::kFailed) {
      std::fflush(stdout);
      std::exit(grade_exit_code(1));
    }
    return;
  }
  if (!o.gather_only) {
    const int threads = std::max(1, thread_count() / o.jobs);
    std::vector<std::string> args = {
        "--threads", std::to_string(threads), "grade", o.design, o.bodies, "--out", o.out};
    if (o.max_iterations >= 0)
      args.insert(args.end(), {"--max-iterations", std::to_string(o.max_iterations)});
    std::printf("tightfit grade: %zu bodies, %d at a time, %d threads each\n", bodies.size(),
                o.jobs, threads);
    std::fflush(stdout);
    run_body_processes(args, names, o.jobs, fs::path(o.out) / "logs");
  }
  const int not_graded = gather(o, bodies);
  if (not_graded > 0) {
    std::fflush(stdout);
    std::exit(grade_exit_code(not_graded));
  }
}

const CommandRegistration kGrade{
    "grade", [](CLI::App& root) {
      auto [cmd, o] = add_command<GradeOptions>(
          root,
          {"grade",
           "Grade one design over a population of bodies: optimize the design scene on every "
           "body of BODIES (its body mesh and rig joints replaced), each in DIR/bodies/NAME "
           "(idempotent: a graded body is skipped, a killed one resumes from its checkpoint), "
           "then gather DIR/grade.json, the grading report DIR/grade.html and the nest of every "
           "size's pieces (nest.svg, nest.pdf, nest.dxf). Exit code: 0 all graded, 2 bad input, "
           "10 + the number of bodies not graded.",
           "Example:\n  tightfit grade examples/optimize_wetsuit_regular.json \\\n"
           "      examples/grading/bodies_full.json --out out/grade --jobs 2"},
          [](const GradeOptions& options) { run_grade(options); });
      cmd.add_option(
             "design", o.design,
             "Design scene: a scene with \"optimize\" and a \"rig\" {\"mesh\", \"weights\", "
             "\"joints\"}, with a body \"mesh\" (replaced by each body's) or without \"body\"")
          ->required();
      cmd.add_option("bodies", o.bodies,
                     "Bodies file: {\"bodies\": [{\"name\", \"mesh\", \"joints\", \"rig_mesh\"}]} "
                     "(schema/bodies.schema.json)")
          ->required();
      add_output_options(cmd, o.out, o.force,
                         std::string(kOutHelp) + "; DIR/bodies/NAME belongs to tightfit grade");
      auto* body =
          cmd.add_option("--body", o.body,
                         "Grade this body only (one idempotent invocation, for GNU parallel "
                         "or a Slurm array task); no gathering");
      auto* gather_flag = cmd.add_flag("--gather", o.gather_only,
                                       "Only gather the bodies graded so far into grade.json, "
                                       "grade.html and the nest files");
      cmd.add_option("--jobs", o.jobs,
                     "Bodies graded at once, each in its own process with --threads / N threads "
                     "(default 1)")
          ->check(CLI::Range(1, 1024))
          ->excludes(body)
          ->excludes(gather_flag);
      body->excludes(gather_flag);
      cmd.add_option("--max-iterations", o.max_iterations,
                     "Stop each body after this many L-BFGS iterations (overrides the design's "
                     "optimize/max_iterations)")
          ->check(non_negative_number());
      cmd.add_option("--nest-seam", o.nest_seam,
                     "Align the nest at the start of this seam (where its first notch sits) "
                     "instead of the pieces' centroids");
    }};

}  // namespace
}  // namespace tightfit::app
