#include "grade_jobs.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <thread>

#include "tightfit/common/error.hpp"
#include "tightfit/common/interrupt.hpp"

extern char** environ;

namespace tightfit::app {
namespace {

namespace fs = std::filesystem;

/// Starts one body's process; returns its pid.
pid_t spawn_body(const std::vector<std::string>& args, const std::string& name,
                 const fs::path& log) {
  std::vector<std::string> words = {"/proc/self/exe"};
  words.insert(words.end(), args.begin(), args.end());
  words.insert(words.end(), {"--body", name});
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  // A process group of its own: Ctrl-C reaches this process only, which passes one
  // SIGTERM on (a second signal would end a body before it writes its checkpoint).
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  pid_t pid = -1;
  const int error =
      posix_spawn(&pid, "/proc/self/exe", &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (error != 0)
    throw std::runtime_error("cannot start the process of body " + name + ": " +
                             std::strerror(error));
  return pid;
}

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

}  // namespace

std::vector<BodyProcess> run_body_processes(const std::vector<std::string>& args,
                                            const std::vector<std::string>& names, int jobs,
                                            const fs::path& log_dir) {
  std::error_code ec;
  fs::create_directories(log_dir, ec);
  if (ec) throw InputError(log_dir.string(), "cannot create the log folder: " + ec.message());
  std::vector<BodyProcess> results;
  for (const std::string& name : names) results.push_back({name, -1});
  std::map<pid_t, size_t> running;
  size_t next = 0;
  bool stopping = false;
  const InterruptGuard interrupts;
  while (next < names.size() || !running.empty()) {
    if (interrupt_requested() && !stopping) {
      stopping = true;
      for (const auto& [pid, k] : running) ::kill(pid, SIGTERM);
    }
    while (!stopping && next < names.size() && static_cast<int>(running.size()) < jobs) {
      const fs::path log = log_dir / (names[next] + ".log");
      running[spawn_body(args, names[next], log)] = next;
      std::printf("  body %s started (log %s)\n", names[next].c_str(), log.c_str());
      std::fflush(stdout);
      ++next;
    }
    if (stopping && running.empty()) break;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    BodyProcess& r = results[it->second];
    r.exit_code = exit_code_of(status);
    running.erase(it);
    std::printf("  body %s %s (exit %d)\n", r.name.c_str(),
                r.exit_code == 0 ? "done" : "not graded", r.exit_code);
    std::fflush(stdout);
  }
  if (stopping) throw Interrupted{interrupt_signal()};
  return results;
}

}  // namespace tightfit::app
