#pragma once
/// Threads: how many tightfit's element loops (OpenMP) and the BLAS under CHOLMOD use,
/// and which BLAS library the process runs on.
///
/// The thread count is one number for the whole process: `--threads N` on the command
/// line, else the environment variable TIGHTFIT_THREADS, else the number of cores.
/// Parallel loops split work in fixed contiguous chunks per thread and combine the
/// chunks in thread order, so a run is repeatable bit for bit for a fixed thread
/// count; other counts change results only by round-off.
#include <cstdint>
#include <exception>
#include <string>

namespace tightfit {

/// Sets the thread count of OpenMP loops and of the BLAS (OpenBLAS is told through
/// openblas_set_num_threads when it is the loaded BLAS). Throws std::invalid_argument
/// for n < 1.
void set_thread_count(int n);
/// The thread count in force (set_thread_count, or the default below).
int thread_count();
/// TIGHTFIT_THREADS when set to a positive integer, else the number of cores. Throws
/// std::invalid_argument naming the variable when it is set to anything else.
int default_thread_count();

/// Runs fn(i) for i in [0, n) on thread_count() threads (fixed contiguous chunks; serial
/// below `serial_below` items, where starting threads costs more than it saves). fn must
/// only write to memory owned by item i (e.g. element i's slot of a preallocated
/// array): results are then the same for every thread count, bit for bit. An exception
/// thrown by fn is rethrown after the loop (the one of the lowest i that threw).
template <typename Fn>
void parallel_for(std::int64_t n, Fn&& fn, std::int64_t serial_below = 256) {
  if (n < serial_below || thread_count() == 1) {
    for (std::int64_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::exception_ptr error;
  std::int64_t error_index = n;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    try {
      fn(i);
    } catch (...) {
#pragma omp critical(tightfit_parallel_for_error)
      if (i < error_index) {
        error_index = i;
        error = std::current_exception();
      }
    }
  }
  if (error) std::rethrow_exception(error);
}

/// The BLAS that the process calls (CHOLMOD's supernodal factorization runs on it).
struct BlasInfo {
  std::string library;  ///< resolved path of the shared object that defines dgemm_
  std::string name;     ///< "OpenBLAS", "reference BLAS (netlib)", or the file name
  std::string config;   ///< openblas_get_config() for OpenBLAS, else empty
  int threads = 1;      ///< threads the BLAS may use
};
BlasInfo blas_info();

}  // namespace tightfit
