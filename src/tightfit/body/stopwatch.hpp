#pragma once
/// Wall-clock timing of build stages (steady clock, seconds).
#include <chrono>

namespace tightfit {

class Stopwatch {
 public:
  /// Seconds since construction or the previous lap; restarts the clock.
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace tightfit
