#pragma once
/// Wall-clock timing (steady clock, seconds): the one stopwatch of tightfit's stages,
/// solvers and commands.
#include <chrono>

namespace tightfit {

using SteadyClock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

/// A clock for timing consecutive stages: each lap() returns the seconds since the
/// previous one.
class Stopwatch {
 public:
  /// Seconds since construction or the previous lap; restarts the clock.
  double lap() {
    const auto now = SteadyClock::now();
    const double seconds = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return seconds;
  }

 private:
  SteadyClock::time_point start_ = SteadyClock::now();
};

}  // namespace tightfit
