#pragma once
/// `tightfit grade --jobs N`: the bodies of a grading run locally, N at a time, each as
/// its own process — this binary re-invoked with `--body NAME`, the same idempotent
/// invocation GNU parallel or a Slurm array task runs — so that a crash or the memory
/// of one body does not touch the others.
#include <filesystem>
#include <string>
#include <vector>

namespace tightfit::app {

struct BodyProcess {
  std::string name;
  int exit_code = -1;  ///< the process's exit code; 128 + signal when a signal ended it
};

/// Runs `/proc/self/exe ARGS --body NAME` for every name of `names`, at most `jobs` at
/// a time, each with its stdout and stderr appended to `log_dir`/NAME.log. Prints a line when a
/// body ends. Ctrl-C / SIGTERM: the running bodies get SIGTERM (they finish their
/// iteration and write their checkpoint), no new one starts, and Interrupted is thrown
/// once they have ended. Returns the bodies' exit codes, in the order of `names`.
std::vector<BodyProcess> run_body_processes(const std::vector<std::string>& args,
                                            const std::vector<std::string>& names, int jobs,
                                            const std::filesystem::path& log_dir);

}  // namespace tightfit::app
