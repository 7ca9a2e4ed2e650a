#pragma once
/// Threads: how many tightfit's element loops and the BLAS under CHOLMOD use, and which
/// BLAS library the process runs on.
///
/// Element loops run on a small pool of std::threads that poll for the next loop for
/// 0.2 ms after each one (a futex wake-up costs 2–40 µs on a virtual machine, as much as a
/// small parallel loop), then sleep on a condition variable. OpenMP is not used by tightfit:
/// Debian's CHOLMOD is built with OpenMP teams of a fixed 4 threads (CHOLMOD_OMP_NUM_THREADS) for
/// its memory-bound copy loops, which on a 2-core machine oversubscribe the cores and spend their
/// time in futex wake-ups and yields (system time); set_thread_count() therefore makes OpenMP
/// regions inactive (omp_set_max_active_levels(0)), and the factorization's dense work
/// runs on the BLAS threads.
///
/// The thread count is one number for the whole process: `--threads N` on the command
/// line, else the environment variable TIGHTFIT_THREADS, else the number of cores.
/// Parallel loops split work in fixed contiguous chunks per thread and combine the
/// chunks in thread order, so a run is repeatable bit for bit for a fixed thread
/// count; other counts change results only by round-off.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>

namespace tightfit {

/// Sets the thread count of the element loops and of the BLAS (OpenBLAS is told through
/// openblas_set_num_threads when it is the loaded BLAS; the first call also shortens the
/// spin of OpenBLAS's idle threads to 2^20 cycles unless OPENBLAS_THREAD_TIMEOUT is set). Throws
/// std::invalid_argument for n < 1.
void set_thread_count(int n);
/// The thread count in force (set_thread_count, or the default below).
int thread_count();
/// TIGHTFIT_THREADS when set to a positive integer, else the number of cores. Throws
/// std::invalid_argument naming the variable when it is set to anything else.
int default_thread_count();

/// Runs body(t) for t = 0 … count − 1, each on its own thread of tightfit's pool (t = 0
/// on the calling thread), and returns when all have returned. Called from inside a
/// body, it runs serially on the calling thread (no nested parallelism). Exceptions of
/// the bodies are rethrown here, the one of the lowest t first.
void run_on_threads(int count, const std::function<void(int)>& body);

/// Runs fn(i) for i in [0, n) on thread_count() threads, each taking one fixed
/// contiguous chunk of the range (serial below `serial_below` items, where waking
/// threads costs more than it saves). fn must only write to memory owned by item i
/// (e.g. element i's slot of a preallocated array): results are then the same for
/// every thread count, bit for bit. An exception thrown by fn is rethrown after the
/// loop (the one of the lowest i that threw).
template <typename Fn>
void parallel_for(std::int64_t n, Fn&& fn, std::int64_t serial_below = 256) {
  const int threads = thread_count();
  if (n < serial_below || threads == 1) {
    for (std::int64_t i = 0; i < n; ++i) fn(i);
    return;
  }
  const int chunks = static_cast<int>(std::min<std::int64_t>(threads, n));
  run_on_threads(chunks, [&](int t) {
    const std::int64_t begin = n * t / chunks, end = n * (t + 1) / chunks;
    for (std::int64_t i = begin; i < end; ++i) fn(i);
  });
}

/// The BLAS that the process calls (CHOLMOD's supernodal factorization runs on it).
struct BlasInfo {
  std::string library;  ///< resolved path of the shared object that defines dgemm_
  std::string name;     ///< "OpenBLAS", "reference BLAS (netlib)", or the file name
  std::string config;   ///< openblas_get_config() for OpenBLAS, else empty
  int threads = 1;      ///< threads the BLAS may use
  /// OpenBLAS: its idle threads spin 2^thread_timeout cycles before they sleep (see
  /// set_thread_count); 0 when not known.
  int thread_timeout = 0;
};
BlasInfo blas_info();

}  // namespace tightfit
